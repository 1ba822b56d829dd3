// The occlude 3D viewer (viewer_page.h): both jaws at the pose in three.js r111, coloured
// by the contact map; orbit/zoom/pan; upper jaw solid, transparent or hidden; a click reads
// the distance and the tooth; standard views; a switcher between proposals. Reads its data
// from the JSON element #occlude-viewer-data (layout: viewer_data_internal.h). Frames: the
// lower mesh in L, the upper in U placed by each proposal's X_LU; mm. No network access.
(function () {
  'use strict';
  var FAR_CODE = 32767;
  var BACKGROUND = 0xf4f4f2;
  var root = document.getElementById('occlude-viewer');
  var canvas = document.getElementById('occlude-viewer-canvas');
  var data = JSON.parse(document.getElementById('occlude-viewer-data').textContent);
  var el = function (id) { return document.getElementById('occlude-viewer-' + id); };
  var state = { proposal: 0, view: 'oblique', upper: 'solid', lower: true, pick: null };
  // performance.now() (ms from the navigation's start) at each step of the first draw.
  var timings = { page: window.occludeViewerStart, script: performance.now() };

  // --- data ------------------------------------------------------------------------------
  function bytes(b64) {
    if (Uint8Array.fromBase64) return Uint8Array.fromBase64(b64);  // native where there is one
    var s = atob(b64), out = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
    return out;
  }
  // Little-endian typed arrays (every platform a browser runs on is little-endian).
  function typed(type, b64) {
    var b = bytes(b64);
    if (type === 'uint8') return b;
    if (type === 'uint16') return new Uint16Array(b.buffer);
    if (type === 'int16') return new Int16Array(b.buffer);
    if (type === 'uint32') return new Uint32Array(b.buffer);
    throw new Error('unknown array type ' + type);
  }
  function decodeJaw(jaw) {
    var q = typed('uint16', jaw.positions.data), o = jaw.positions.origin;
    var s = jaw.positions.step, pos = new Float32Array(q.length);
    for (var i = 0; i < q.length; i += 3) {
      pos[i] = o[0] + q[i] * s[0];
      pos[i + 1] = o[1] + q[i + 1] * s[1];
      pos[i + 2] = o[2] + q[i + 2] * s[2];
    }
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    g.setIndex(new THREE.BufferAttribute(typed(jaw.index.type, jaw.index.data), 1));
    g.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(pos.length), 3, true));
    g.computeVertexNormals();
    g.computeBoundingSphere();
    return { geometry: g, part: typed(jaw.part.type, jaw.part.data), names: jaw.part.names };
  }
  function decodeSurface(s) {
    return { distance: typed('int16', s.distance_um), colour: bytes(s.colour) };
  }

  // --- scene -----------------------------------------------------------------------------
  // The WebGL renderer's name; software ones (SwiftShader, llvmpipe: no GPU) draw
  // multisampling on the CPU, so the page does without it there.
  function probeRenderer() {
    try {
      var probe = document.createElement('canvas').getContext('webgl');
      var info = probe && probe.getExtension('WEBGL_debug_renderer_info');
      var name = info ? String(probe.getParameter(info.UNMASKED_RENDERER_WEBGL)) : '';
      var lose = probe && probe.getExtension('WEBGL_lose_context');
      if (lose) lose.loseContext();
      return name;
    } catch (e) {
      return '';
    }
  }
  var rendererInfo = probeRenderer();
  var software = /SwiftShader|llvmpipe|software/i.test(rendererInfo);
  var renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: !software,
                                           preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(BACKGROUND, 1);
  var scene = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(30, 1, 1, 1000);
  scene.add(camera);
  scene.add(new THREE.AmbientLight(0xffffff, 0.5));
  var headlight = new THREE.DirectionalLight(0xffffff, 0.6);
  headlight.position.set(0.3, 0.6, 1);
  camera.add(headlight);
  var jaws = data.jaws.map(decodeJaw);
  var proposals = data.proposals.map(function (p) {
    return { lower: decodeSurface(p.lower), upper: decodeSurface(p.upper) };
  });
  timings.decoded = performance.now();
  var meshes = jaws.map(function (jaw, i) {
    var m = new THREE.Mesh(jaw.geometry, new THREE.MeshLambertMaterial({
      vertexColors: THREE.VertexColors, side: THREE.DoubleSide }));
    m.userData.jaw = i;
    scene.add(m);
    return m;
  });
  meshes[1].matrixAutoUpdate = false;
  var marker = new THREE.Mesh(new THREE.SphereBufferGeometry(1, 16, 12),
                              new THREE.MeshBasicMaterial({ color: 0x111111 }));
  marker.visible = false;
  scene.add(marker);
  var controls = new THREE.OrbitControls(camera, canvas);
  controls.screenSpacePanning = true;
  var axes = {};
  ['occlusal', 'anterior', 'lateral'].forEach(function (k) {
    axes[k] = new THREE.Vector3().fromArray(data.axes[k]);
  });

  var live = false;  // no drawing until the scene is set up (one first frame, not several)
  function render() { if (live) renderer.render(scene, camera); }
  function resize() {
    var w = Math.max(canvas.clientWidth, 1), h = Math.max(canvas.clientHeight, 1);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }

  // --- proposals, jaws, views ------------------------------------------------------------
  function setProposal(i) {
    i = Math.max(0, Math.min(proposals.length - 1, i | 0));
    state.proposal = i;
    meshes[1].matrix.fromArray(data.proposals[i].X_LU);
    meshes[1].matrixWorldNeedsUpdate = true;
    ['lower', 'upper'].forEach(function (name, j) {
      var attr = meshes[j].geometry.getAttribute('color');
      attr.array.set(proposals[i][name].colour);
      attr.needsUpdate = true;
    });
    showNumbers(data.proposals[i]);
    var buttons = el('proposals').querySelectorAll('button');
    for (var b = 0; b < buttons.length; b++) {
      buttons[b].setAttribute('aria-pressed', b === i ? 'true' : 'false');
    }
    if (state.pick) pickAt(state.pick.x, state.pick.y);
    document.body.dataset.viewerProposal = String(i);
    render();
  }
  function setUpperMode(mode) {
    state.upper = mode;
    var mat = meshes[1].material;
    meshes[1].visible = mode !== 'hidden';
    mat.transparent = mode === 'transparent';
    mat.opacity = mode === 'transparent' ? 0.4 : 1;
    mat.depthWrite = mode !== 'transparent';
    mat.needsUpdate = true;
    el('upper').value = mode;
    render();
  }
  function setLowerVisible(on) {
    state.lower = !!on;
    meshes[0].visible = state.lower;
    el('lower').checked = state.lower;
    render();
  }
  // The bounding sphere of both jaws at the current pose, in L.
  function bounds() {
    scene.updateMatrixWorld();
    var box = new THREE.Box3().setFromObject(meshes[0]).union(
      new THREE.Box3().setFromObject(meshes[1]));
    return box.getBoundingSphere(new THREE.Sphere());
  }
  var VIEWS = {
    oblique: function () {
      return [axes.anterior.clone().addScaledVector(axes.occlusal, 0.35)
                .addScaledVector(axes.lateral, -0.6), axes.occlusal];
    },
    'occlusal-lower': function () { return [axes.occlusal, axes.anterior]; },
    'occlusal-upper': function () { return [axes.occlusal.clone().negate(), axes.anterior]; },
    frontal: function () { return [axes.anterior, axes.occlusal]; },
    right: function () { return [axes.lateral.clone().negate(), axes.occlusal]; },
    left: function () { return [axes.lateral, axes.occlusal]; }
  };
  function setView(name) {
    if (!VIEWS[name]) throw new Error('unknown view ' + name);
    state.view = name;
    if (name === 'occlusal-lower') { setLowerVisible(true); setUpperMode('hidden'); }
    else if (name === 'occlusal-upper') { setLowerVisible(false); setUpperMode('solid'); }
    else { setLowerVisible(true); if (state.upper === 'hidden') setUpperMode('solid'); }
    var dirUp = VIEWS[name](), s = bounds();
    var dist = s.radius / Math.sin(THREE.Math.degToRad(camera.fov / 2)) * 0.8;
    camera.near = dist / 50;
    camera.far = dist * 4;
    camera.up.copy(dirUp[1]).normalize();
    camera.position.copy(s.center).addScaledVector(dirUp[0].clone().normalize(), dist);
    camera.lookAt(s.center);
    camera.updateProjectionMatrix();
    controls.target.copy(s.center);
    controls.update();
    marker.scale.setScalar(s.radius / 150);
    render();
  }

  // --- reading the surface ---------------------------------------------------------------
  var raycaster = new THREE.Raycaster();
  // What a click at canvas pixel (x, y) (CSS pixels from the top left) reads.
  function pickAt(x, y) {
    var rect = canvas.getBoundingClientRect();
    var ndc = new THREE.Vector2(x / rect.width * 2 - 1, 1 - y / rect.height * 2);
    scene.updateMatrixWorld();
    raycaster.setFromCamera(ndc, camera);
    var hits = raycaster.intersectObjects(meshes.filter(function (m) { return m.visible; }));
    state.pick = { x: x, y: y };
    if (!hits.length) {
      state.pick.result = { hit: false };
      marker.visible = false;
      el('pick').textContent = 'No surface there.';
      render();
      return state.pick.result;
    }
    var h = hits[0], j = h.object.userData.jaw, jaw = jaws[j];
    var result = readHit(h, j, jaw);
    marker.position.copy(h.point);
    marker.visible = true;
    state.pick.result = result;
    el('pick').textContent = describePick(result);
    render();
    return result;
  }
  function readHit(h, j, jaw) {
    var local = h.object.worldToLocal(h.point.clone());
    var pos = jaw.geometry.getAttribute('position');
    var corners = [h.face.a, h.face.b, h.face.c];
    var v = corners.map(function (k) { return new THREE.Vector3().fromBufferAttribute(pos, k); });
    var w = THREE.Triangle.getBarycoord(local, v[0], v[1], v[2], new THREE.Vector3());
    var dist = proposals[state.proposal][j === 0 ? 'lower' : 'upper'].distance;
    var far = false, d = 0, weights = [w.x, w.y, w.z];
    corners.forEach(function (k, i) {
      if (dist[k] === FAR_CODE) far = true;
      d += weights[i] * dist[k];
    });
    var part = jaw.names[jaw.part[h.faceIndex]] || { name: '', fdi: 0, universal: 0 };
    return { hit: true, jaw: j === 0 ? 'lower' : 'upper', far: far,
             distance_mm: far ? null : d / 1000, tooth_fdi: part.fdi,
             tooth_universal: part.universal, part: part.name,
             point_L: [h.point.x, h.point.y, h.point.z] };
  }
  function describePick(r) {
    var where = (r.jaw === 'lower' ? 'Lower' : 'Upper') + ' jaw, ' +
      (r.tooth_fdi ? 'tooth ' + r.tooth_fdi + ' (FDI; Universal ' + r.tooth_universal + ')'
                   : (r.part || 'not a tooth'));
    if (r.far) return where + ': the opposing jaw is out of reach here.';
    var d = r.distance_mm;
    var what = d < -data.scale.penetration_from_mm ? 'penetration ' + (-d).toFixed(3) + ' mm'
             : d <= data.scale.band_mm ? 'contact, gap ' + d.toFixed(3) + ' mm'
             : 'gap ' + d.toFixed(3) + ' mm';
    return where + ': ' + what + '.';
  }

  // --- panels ----------------------------------------------------------------------------
  function showNumbers(p) {
    var table = el('numbers');
    table.textContent = '';
    var caption = document.createElement('caption');
    caption.textContent = p.label;
    table.appendChild(caption);
    Object.keys(p.numbers).forEach(function (k) {
      var tr = document.createElement('tr'), th = document.createElement('th');
      var td = document.createElement('td'), v = p.numbers[k];
      th.textContent = k;
      td.textContent = typeof v === 'number' ? String(+v.toPrecision(6)) : JSON.stringify(v);
      if (typeof v === 'string') td.textContent = v;
      tr.appendChild(th);
      tr.appendChild(td);
      table.appendChild(tr);
    });
  }
  function buildLegend() {
    var sc = data.scale, stops = sc.ramp.map(function (s) {
      return s[1] + ' ' + (100 * s[0] / sc.max_mm).toFixed(1) + '%';
    });
    el('ramp').style.background = 'linear-gradient(to right, ' + stops.join(', ') + ')';
    el('ramp-labels').textContent = '0 mm \u2192 ' + sc.max_mm + ' mm (contact band 0\u2013' +
      sc.band_mm + ' mm in red to orange)';
    el('pen-swatch').style.background = sc.penetration;
    el('far-swatch').style.background = sc.far;
    el('pen-label').textContent = 'penetration deeper than ' + sc.penetration_from_mm + ' mm';
    el('far-label').textContent = 'farther than ' + sc.max_mm + ' mm';
  }
  function buildProposalButtons() {
    el('proposals').textContent = '';
    data.proposals.forEach(function (p, i) {
      var b = document.createElement('button');
      b.type = 'button';
      b.textContent = p.label;
      b.addEventListener('click', function () { setProposal(i); });
      el('proposals').appendChild(b);
    });
  }
  function buildControls() {
    buildProposalButtons();
    var views = root.querySelectorAll('[data-view]');
    for (var i = 0; i < views.length; i++) {
      views[i].addEventListener('click', function (e) { setView(e.target.dataset.view); });
    }
    el('upper').addEventListener('change', function (e) { setUpperMode(e.target.value); });
    el('lower').addEventListener('change', function (e) { setLowerVisible(e.target.checked); });
    var down = null;
    canvas.addEventListener('mousedown', function (e) { down = [e.clientX, e.clientY]; });
    canvas.addEventListener('click', function (e) {
      if (!down || Math.abs(e.clientX - down[0]) + Math.abs(e.clientY - down[1]) > 4) return;
      var rect = canvas.getBoundingClientRect();
      pickAt(e.clientX - rect.left, e.clientY - rect.top);
    });
    controls.addEventListener('change', render);
    window.addEventListener('resize', function () { resize(); render(); });
  }

  // --- live pages: proposals pushed as server-sent events (viewer_page.h) ----------------
  function receiveProposal(p) {
    var i = 0;
    while (i < data.proposals.length && data.proposals[i].label !== p.label) i++;
    data.proposals[i] = p;
    proposals[i] = { lower: decodeSurface(p.lower), upper: decodeSurface(p.upper) };
    buildProposalButtons();
    setProposal(i);
    var gl = renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));  // the frame is done
    document.body.dataset.viewerUpdates = String(Number(document.body.dataset.viewerUpdates) + 1);
    document.body.dataset.viewerUpdatedAt = String(Date.now());
  }
  function listen(path) {
    document.body.dataset.viewerUpdates = '0';
    var source = new EventSource(path);
    source.onopen = function () {
      document.body.dataset.viewerLive = 'open';
      el('status').textContent = 'Live: each new refinement is shown here as it arrives.';
    };
    source.onerror = function () {  // the server stopped (it retries while it can)
      document.body.dataset.viewerLive = 'closed';
      el('status').textContent = 'The live refinement stopped; this page keeps the last pose.';
    };
    source.addEventListener('proposal', function (e) { receiveProposal(JSON.parse(e.data)); });
  }

  // --- for tests and tools ---------------------------------------------------------------
  var snapshot = null;
  function readPixels() {
    render();
    var gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    var px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return { w: w, h: h, px: px };
  }
  // Pixels that differ from the background, and an FNV-1a checksum of the whole canvas.
  function drawnPixels() {
    var r = readPixels(), bg = new THREE.Color(BACKGROUND), drawn = 0, sum = 2166136261;
    var b = [bg.r * 255, bg.g * 255, bg.b * 255];
    for (var i = 0; i < r.px.length; i += 4) {
      if (Math.abs(r.px[i] - b[0]) + Math.abs(r.px[i + 1] - b[1]) +
          Math.abs(r.px[i + 2] - b[2]) > 6) drawn++;
    }
    for (var k = 0; k < r.px.length; k++) sum = Math.imul(sum ^ r.px[k], 16777619) >>> 0;
    return { drawn: drawn, total: r.w * r.h, checksum: sum };
  }
  function takeSnapshot() { snapshot = readPixels().px; }
  // Pixels that changed since takeSnapshot() (-1 without one or after a resize).
  function changedSinceSnapshot() {
    var now = readPixels().px, n = 0;
    if (!snapshot || snapshot.length !== now.length) return -1;
    for (var i = 0; i < now.length; i += 4) {
      if (now[i] !== snapshot[i] || now[i + 1] !== snapshot[i + 1] ||
          now[i + 2] !== snapshot[i + 2]) n++;
    }
    return n;
  }
  window.occludeViewer = {
    setProposal: setProposal, setView: setView, setUpperMode: setUpperMode,
    setLowerVisible: setLowerVisible, pickAt: pickAt, drawnPixels: drawnPixels,
    takeSnapshot: takeSnapshot, changedSinceSnapshot: changedSinceSnapshot,
    state: function () {
      return { proposal: state.proposal, proposals: proposals.length, view: state.view,
               upper: state.upper, lower: state.lower,
               pick: state.pick ? state.pick.result : null,
               canvas: [canvas.width, canvas.height],
               triangles: data.jaws.map(function (j) { return j.triangles; }),
               errors: (window.occludeViewerErrors || []).slice(), timings: timings,
               renderer: rendererInfo, antialias: !software };
    }
  };

  buildLegend();
  buildControls();
  resize();
  setProposal(0);
  setView('oblique');
  timings.scene = performance.now();
  live = true;
  render();
  var gl = renderer.getContext();
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));  // the frame is done
  timings.first_draw = performance.now();
  document.body.dataset.viewerFirstDrawMs = String(Math.round(timings.first_draw));
  document.body.dataset.viewerReady = '1';
  el('status').textContent = 'Drag to turn, scroll to zoom, right-drag to pan; click a surface ' +
    'to read the gap there.';
  if (data.live) listen(data.live);
})();
