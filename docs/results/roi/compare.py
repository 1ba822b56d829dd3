# Compares the runs of run.sh (in the current folder): pose and contact differences, peak RSS,
# wall time, and each oracle's memory, build time and region (metrics.json settings.oracles).
import json,math,re
rows=[]
for c in ['a-bite-3shape','b-open-3shape']:
  for b in ['default','narrow']:
    r={}
    for roi in ['true','false']:
      d=f'out-{c}-{b}-{roi}'
      m=json.load(open(d+'/metrics.json')); p=json.load(open(d+'/pose.json'))
      err=open(f'{c}-{b}-roi-{roi}.stderr').read()
      rss=int(re.search(r'Maximum resident set size \(kbytes\): (\d+)',err).group(1))
      wall=re.search(r'Elapsed \(wall clock\) time.*: (\S+)',err).group(1)
      r[roi]=(m,p,rss,wall)
    (m1,p1,rss1,w1),(m0,p0,rss0,w0)=r['true'],r['false']
    dt=max(abs(a-b) for a,b in zip(p1['translation_mm'],p0['translation_mm']))
    dr=max(abs(a-b) for a,b in zip(p1['rotation_deg'],p0['rotation_deg']))
    def orc(m): return m['settings']['oracles']
    def ca(m):
      for k in ['contact_area_mm2']:
        if k in m: return m[k]
      return m.get('contact',{}).get('area_mm2')
    print(f'== {c} {b}: pose diff {dt:.4f} mm {dr:.4f} deg; contact {ca(m1)} vs {ca(m0)}; RSS {rss1/1024:.0f} vs {rss0/1024:.0f} MB; wall {w1} vs {w0}')
    for roi,m in [('on',m1),('off',m0)]:
      for o in orc(m):
        reg=o['region_of_interest']
        s=f"  ROI {roi}: {o['voxel_mm']} mm  {o['bytes']/2**20:.1f} MiB  build {o['build_s']:.2f} s"
        if reg: s+=f"  kept lower {reg['lower_kept']}/{reg['lower_total']} upper {reg['upper_kept']}/{reg['upper_total']} R {reg['reach_mm']:.1f} select {reg['select_s']:.2f}s"
        print(s)
