// The live page of `occlude refine CONFIG --watch --serve [PORT] [--bind ADDR]`: the 3D view
// (report/report_viewer.h) of the latest refinement, served by serve/live_server.h on
// 127.0.0.1 (another address only with --bind, with a warning), and each new refinement
// pushed to every open page as a `proposal` event that replaces the one shown, with its
// before/after numbers. Private to the cli part (cmd_refine.cpp).
#pragma once

#include <memory>
#include <string>

#include "report/report_analysis.h"
#include "report/report_viewer.h"
#include "serve/live_server.h"
#include "session/case_session.h"

namespace occlude::app {

class RefineLivePage {
 public:
  /// Listens on `bind` (empty: 127.0.0.1) at `port` (0: any free port). Throws UserError
  /// naming --bind or --serve (an address refused, a port in use).
  RefineLivePage(const std::string& bind, int port);

  /// The display jaws of `session`, decimated again only when its meshes changed.
  const DisplayJaws& Display(const CaseSession& session);
  /// Shows `analysis` (the refined pose of `session`) with `numbers_json` (a JSON object):
  /// the first call and any call after the meshes changed set the page (open pages must be
  /// reloaded then: false); the others push it to the open pages (true).
  bool Show(const CaseSession& session, const ReportAnalysis& analysis,
            const std::string& numbers_json);

  std::string url() const { return server_->url(); }
  LiveServer& server() { return *server_; }

 private:
  std::unique_ptr<LiveServer> server_;
  const io::TriangleMesh* shown_lower_ = nullptr;  ///< the session mesh `display_` is from
  const io::TriangleMesh* shown_upper_ = nullptr;
  DisplayJaws display_;
  bool page_set_ = false;
};

}  // namespace occlude::app
