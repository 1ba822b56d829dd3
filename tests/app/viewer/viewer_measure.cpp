// app_viewer_measure: the viewer page of a real case, measured. Analyzes the
// case config's start pose (and, with --poses 3, the pose opened 0.1 mm along the
// occlusal axis and the pose turned 1 deg about it through the pivot) as the
// report does, decimates both jaws for display, writes the page, opens it in
// headless Chromium and prints the page size, the decimation's thread CPU time
// and bound, and the time to first draw (performance.now() at the first finished
// frame, from the navigation's start) over --runs navigations, after a warm-up
// page has started the browser's renderer and GPU processes (run 1 is then the
// page's first load; later runs reuse the browser's compiled-code cache). --screenshots
// also writes a PNG of each standard view beside the page. --live N then serves
// the page with the first pose through app/serve (live_events_path) and pushes the
// other poses N times, printing each push's latency: from before the event is
// encoded here to the page's redraw done (Date.now() there against the system
// clock here: one machine, one clock).
//
// --page FILE measures an existing page instead (e.g. the report.html of `occlude propose`);
// --live-url URL --save CONFIG --saves N opens the live page of a running `occlude refine
// CONFIG --watch --serve` and appends a comment line to CONFIG N times, printing each save's
// latency from the write to the page's redraw done (the refinement in between included).
//
//   build/bin/app_viewer_measure examples/a-bite-3shape.toml --poses 3 --out /tmp/v --live 5
//   build/bin/app_viewer_measure --page out/a-bite/report.html --runs 3 --out /tmp/v
//   build/bin/app_viewer_measure --live-url http://127.0.0.1:8765/ --save case.toml --saves 5
#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "base/timing.h"
#include "config/case_config.h"
#include "headless_browser.h"
#include "occlude/angles.h"
#include "occlude/io/display_decimation.h"
#include "report/report_analysis.h"
#include "serve/live_server.h"
#include "session/case_session.h"
#include "viewer/viewer_page.h"

namespace occlude::app {
namespace {

namespace fs = std::filesystem;

struct Options {
  fs::path config;
  int poses = 1;
  std::size_t budget = 100000;
  int runs = 3;
  fs::path out = "viewer-measure";
  bool screenshots = false;
  int live_pushes = 0;
  std::string eval;  ///< a script expression to evaluate after the runs, printed as JSON
  fs::path page;     ///< measure this page instead of building one
  std::string live_url;
  fs::path save;  ///< the config a running `refine --watch --serve` watches
  int saves = 0;
};

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--poses") {
      o.poses = std::stoi(next());
    } else if (a == "--budget") {
      o.budget = std::stoul(next());
    } else if (a == "--runs") {
      o.runs = std::stoi(next());
    } else if (a == "--out") {
      o.out = next();
    } else if (a == "--screenshots") {
      o.screenshots = true;
    } else if (a == "--live") {
      o.live_pushes = std::stoi(next());
    } else if (a == "--eval") {
      o.eval = next();
    } else if (a == "--page") {
      o.page = next();
    } else if (a == "--live-url") {
      o.live_url = next();
    } else if (a == "--save") {
      o.save = next();
    } else if (a == "--saves") {
      o.saves = std::stoi(next());
    } else {
      o.config = a;
    }
  }
  const bool measure_only = !o.page.empty() || !o.live_url.empty();
  if ((o.config.empty() && !measure_only) || o.poses < 1 || o.poses > 3 || o.runs < 1 ||
      (!o.live_url.empty() && (o.save.empty() || o.saves < 1))) {
    throw std::invalid_argument(
        "usage: app_viewer_measure CONFIG [--poses 1..3] [--budget TRIANGLES] [--runs N] "
        "[--out DIR] [--screenshots] [--live PUSHES] [--eval EXPRESSION]\n"
        "       app_viewer_measure --page FILE [--runs N] [--out DIR] [--screenshots]\n"
        "       app_viewer_measure --live-url URL --save CONFIG --saves N");
  }
  return o;
}

std::vector<Eigen::Isometry3d> Poses(CaseSession& session, int n) {
  const Eigen::Isometry3d start = session.ConfigStartPose();
  const Eigen::Vector3d axis = session.arch().occlusal_L;
  const Eigen::Vector3d pivot = session.pivot_L();
  const Eigen::Isometry3d opened = Eigen::Translation3d(0.1 * axis) * start;
  const Eigen::Isometry3d turned = Eigen::Translation3d(pivot) *
                                   Eigen::AngleAxisd(RadiansFromDegrees(1.0), axis) *
                                   Eigen::Translation3d(-pivot) * start;
  std::vector<Eigen::Isometry3d> all = {start, opened, turned};
  all.resize(static_cast<std::size_t>(n));
  return all;
}

std::string Numbers(const ReportAnalysis& a) {
  std::ostringstream s;
  s << "{\"contact area (mm\\u00b2)\": " << a.oracle.contact_area_mm2
    << ", \"contact spots\": " << a.spots.size()
    << ", \"max penetration (mm)\": " << a.oracle.max_penetration_mm << "}";
  return s.str();
}

// Decimates both jaws (thread CPU time printed) and fills the inputs' meshes and axes.
void Decimate(const CaseSession& session, const Options& o, io::DecimationResult* lower,
              io::DecimationResult* upper, ViewerInputs* in) {
  const double t0 = ThreadCpuSeconds();
  *lower = io::DecimateForDisplay(*session.jaws().lower_L, {o.budget});
  const double t1 = ThreadCpuSeconds();
  *upper = io::DecimateForDisplay(*session.jaws().upper_U, {o.budget});
  const double t2 = ThreadCpuSeconds();
  std::cout << "lower: " << session.jaws().lower_L->num_triangles() << " -> "
            << lower->mesh.num_triangles() << " triangles, cell " << lower->cell_mm << " mm, bound "
            << lower->error_bound_mm << " mm, " << (t1 - t0) << " s CPU\n"
            << "upper: " << session.jaws().upper_U->num_triangles() << " -> "
            << upper->mesh.num_triangles() << " triangles, cell " << upper->cell_mm << " mm, bound "
            << upper->error_bound_mm << " mm, " << (t2 - t1) << " s CPU\n";
  in->lower_L = &lower->mesh;
  in->upper_U = &upper->mesh;
  const collision::ArchFrame& arch = session.arch();
  in->axes = {arch.occlusal_L, arch.anterior_L, arch.lateral_L};
  in->scale.max_mm = session.config().report.map_max_mm;
  in->scale.band_mm = session.config().contact_band_mm;
  in->scale.penetration_from_mm = session.config().report.map_penetration_from_mm;
}

void Measure(const fs::path& page, const Options& o) {
  std::string why;
  auto browser = test::HeadlessBrowser::Launch(&why);
  if (!browser) throw std::runtime_error("no headless browser: " + why);
  // A browser already running, as a user's is: its first page and GPU process started.
  std::ofstream(o.out / "warm-up.html") << "<canvas id=c></canvas><script>document.getElementById"
                                           "('c').getContext('webgl').clear(16384)</script>";
  browser->Navigate("file://" + fs::absolute(o.out / "warm-up.html").string(), 120);
  for (int run = 0; run < o.runs; ++run) {
    const double t0 = NowSeconds();
    const double cpu0 = browser->CpuSeconds();
    browser->Navigate("file://" + fs::absolute(page).string(), 120);
    if (!browser->WaitFor("document.body.dataset.viewerReady === '1'", 120)) {
      throw std::runtime_error("the page did not draw");
    }
    std::cout << "run " << run + 1 << ": first draw at "
              << browser->Evaluate("document.body.dataset.viewerFirstDrawMs").get<std::string>()
              << " ms after the navigation started (" << (NowSeconds() - t0) * 1000
              << " ms wall here, load event and polling included; browser CPU "
              << browser->CpuSeconds() - cpu0 << " s); errors: " << browser->Errors().size()
              << "; steps (ms from the start): "
              << browser->Evaluate("occludeViewer.state().timings").dump() << "\n";
  }
  std::cout << "renderer: " << browser->Evaluate("occludeViewer.state().renderer").dump()
            << ", antialias " << browser->Evaluate("occludeViewer.state().antialias").dump()
            << "\n";
  if (!o.eval.empty()) std::cout << "eval: " << browser->Evaluate(o.eval).dump() << "\n";
  if (!o.screenshots) return;
  browser->Evaluate("document.getElementById('occlude-viewer').scrollIntoView()");  // in a report
  for (const char* view : {"oblique", "occlusal-lower", "occlusal-upper", "frontal", "right"}) {
    browser->Evaluate(std::string("occludeViewer.setView('") + view + "')");
    std::ofstream(o.out / (std::string("viewer-") + view + ".png"), std::ios::binary)
        << browser->Screenshot();
  }
}

double SystemMs() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

void MeasureLive(ViewerInputs in, const Options& o) {
  const std::vector<ViewerProposal> poses = in.proposals;
  in.proposals.resize(1);
  in.live_events_path = "/events";
  LiveServer server({});
  server.SetPage(ViewerPage(in));
  std::string why;
  auto browser = test::HeadlessBrowser::Launch(&why);
  if (!browser) throw std::runtime_error("no headless browser: " + why);
  browser->Navigate(server.url(), 120);
  if (!browser->WaitFor("document.body.dataset.viewerReady === '1' && "
                        "document.body.dataset.viewerLive === 'open'",
                        120)) {
    throw std::runtime_error("the live page did not draw or connect");
  }
  for (int k = 1; k <= o.live_pushes; ++k) {
    ViewerProposal p = poses[static_cast<std::size_t>(k) % poses.size()];
    p.label = "refined";
    const double sent_ms = SystemMs(), cpu0 = ThreadCpuSeconds();
    const std::string event = ViewerProposalEvent(in, p);
    const double encode_s = ThreadCpuSeconds() - cpu0;
    server.Publish("proposal", event);
    const std::string done = "document.body.dataset.viewerUpdates === '" + std::to_string(k) + "'";
    if (!browser->WaitFor(done, 60)) throw std::runtime_error("the live page did not redraw");
    const double drawn_ms =
        std::stod(browser->Evaluate("document.body.dataset.viewerUpdatedAt").get<std::string>());
    std::cout << "push " << k << ": " << event.size() << " bytes, encoded in " << encode_s
              << " s CPU, redrawn " << drawn_ms - sent_ms << " ms after the push began\n";
  }
  std::cout << "live page errors: " << browser->Errors().size() << "\n";
}

// Save-to-redraw latency of a running `refine --watch --serve` (see the opening comment).
void MeasureSaves(const Options& o) {
  std::string why;
  auto browser = test::HeadlessBrowser::Launch(&why);
  if (!browser) throw std::runtime_error("no headless browser: " + why);
  browser->Navigate(o.live_url, 120);
  if (!browser->WaitFor("document.body.dataset.viewerReady === '1' && "
                        "document.body.dataset.viewerLive === 'open'",
                        120)) {
    throw std::runtime_error("the live page did not draw or connect");
  }
  for (int k = 1; k <= o.saves; ++k) {
    const double saved_ms = SystemMs();
    std::ofstream(o.save, std::ios::app) << "# app_viewer_measure save " << k << "\n";
    const std::string done = "document.body.dataset.viewerUpdates === '" + std::to_string(k) + "'";
    if (!browser->WaitFor(done, 300)) throw std::runtime_error("the live page did not redraw");
    const double drawn_ms =
        std::stod(browser->Evaluate("document.body.dataset.viewerUpdatedAt").get<std::string>());
    std::cout << "save " << k << ": redrawn " << drawn_ms - saved_ms << " ms after the write\n";
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  std::cout << "live page errors: " << browser->Errors().size() << "\n";
}

int Run(int argc, char** argv) {
  const Options o = Parse(argc, argv);
  if (!o.live_url.empty()) {
    MeasureSaves(o);
    return 0;
  }
  if (!o.page.empty()) {
    fs::create_directories(o.out);
    std::cout << "page: " << fs::file_size(o.page) << " bytes (" << fs::file_size(o.page) / 1e6
              << " MB)\n";
    Measure(o.page, o);
    return 0;
  }
  CaseSession session(LoadCaseConfig(o.config));
  io::DecimationResult lower, upper;
  ViewerInputs in;
  Decimate(session, o, &lower, &upper, &in);
  in.title = session.config().name + " at the pose";
  for (const Eigen::Isometry3d& X_LU : Poses(session, o.poses)) {
    const ReportAnalysis a = AnalyzePose(session, X_LU);
    ViewerProposal p;
    p.label = "pose " + std::to_string(in.proposals.size() + 1);
    p.X_LU = X_LU;
    p.numbers_json = Numbers(a);
    p.lower_distance_mm = io::ValuesAtKeptVertices(lower, a.lower_vertex_mm);
    p.upper_distance_mm = io::ValuesAtKeptVertices(upper, a.upper_vertex_mm);
    in.proposals.push_back(std::move(p));
  }
  const double t0 = ThreadCpuSeconds();
  const std::string html = ViewerPage(in);
  std::cout << "page: " << html.size() << " bytes (" << html.size() / 1e6 << " MB), "
            << in.proposals.size() << " poses, built in " << ThreadCpuSeconds() - t0 << " s CPU\n";
  fs::create_directories(o.out);
  const fs::path page = o.out / "viewer.html";
  std::ofstream(page, std::ios::binary) << html;
  Measure(page, o);
  if (o.live_pushes > 0) MeasureLive(in, o);
  return 0;
}

}  // namespace
}  // namespace occlude::app

int main(int argc, char** argv) {
  try {
    return occlude::app::Run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "app_viewer_measure: " << e.what() << "\n";
    return 1;
  }
}
