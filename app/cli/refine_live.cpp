// The live page of `refine --watch --serve` (see refine_live.h).
#include "cli/refine_live.h"

#include <iostream>
#include <stdexcept>

#include "base/user_error.h"

namespace occlude::app {
namespace {

constexpr const char* kEventsPath = "/events";
constexpr const char* kLabel = "latest refinement";

}  // namespace

RefineLivePage::RefineLivePage(const std::string& bind, int port) {
  LiveServerOptions options;
  options.port = port;
  if (!bind.empty()) {
    options.address = bind;
    options.allow_non_loopback = true;
    options.warn = [](const std::string& what) {
      std::cerr << "occlude: warning: " << what << "\n";
    };
  }
  try {
    server_ = std::make_unique<LiveServer>(options);
  } catch (const std::invalid_argument& e) {
    throw UserError("--bind " + options.address + ": " + e.what());
  } catch (const std::runtime_error& e) {
    throw UserError("--serve " + std::to_string(port) + ": " + e.what());
  }
}

const DisplayJaws& RefineLivePage::Display(const CaseSession& session) {
  const JawPair& jaws = session.jaws();
  if (jaws.lower_L.get() != shown_lower_ || jaws.upper_U.get() != shown_upper_) {
    display_ = DecimateJawsForViewer(jaws, session.cache().get());
    shown_lower_ = jaws.lower_L.get();
    shown_upper_ = jaws.upper_U.get();
    page_set_ = false;
  }
  return display_;
}

bool RefineLivePage::Show(const CaseSession& session, const ReportAnalysis& analysis,
                          const std::string& numbers_json) {
  const DisplayJaws& display = Display(session);
  ViewerInputs in = ReportViewerInputs(session, display);
  in.title = "Live refinement: " + session.config().name;
  in.live_events_path = kEventsPath;
  const ViewerProposal latest = ViewerProposalOf(display, analysis, kLabel, numbers_json);
  if (page_set_) {
    server_->Publish("proposal", ViewerProposalEvent(in, latest));
    return true;
  }
  in.proposals = {latest};
  server_->SetPage(ViewerPage(in));
  page_set_ = true;
  return false;
}

}  // namespace occlude::app
