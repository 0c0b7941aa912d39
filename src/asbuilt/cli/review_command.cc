// `asbuilt review OUT/` — check and correct a survey on its photo in the
// browser (docs/review.md). The first line of stdout is the page's address
// with its token; logs go to stderr; Ctrl-C ends it.

#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <string>

#include "asbuilt/cli/command.h"
#include "asbuilt/review/home_review.h"
#include "asbuilt/review/http.h"
#include "asbuilt/review/review_session.h"
#include "asbuilt/review/training_example.h"

namespace asbuilt::cli {

int RunReviewCommand(int argc, char** argv) {
  CLI::App app(
      "Check and correct a survey in the browser: its photo with the floor and ceiling lines, corners and\n"
      "openings drawn over it, the live plan beside it; every edit re-fits the walls it touches from the\n"
      "image evidence. Serves 127.0.0.1 only, with a random token; prints the address as the first line.\n"
      "A home survey's folder (survey home.json) opens the home's placement: drag rooms, say which doors\n"
      "are one, and every edit re-places the rooms (docs/home.md).",
      "asbuilt review");
  AddCommonFlags(app);
  std::string out_dir;
  ReviewServerOptions options;
  bool no_open = false, export_training = false;
  app.add_option("out", out_dir, "a folder written by `asbuilt survey -o`")->required();
  app.add_option("--port", options.port, "port on 127.0.0.1 (0: a free one)")->capture_default_str();
  app.add_flag("--no-open", no_open, "do not start a browser");
  app.add_flag("--export-training", export_training,
               "write the saved review as a labelled real example (OUT/review/training/: the views, their labels "
               "drawn from the corrected plan, manifest.json, truth.json) and exit; every save writes it too");
  Parse(app, argc, argv);
  options.open_browser = !no_open;
  options.Check();

  auto serve = [&](ReviewBackend& backend) {
    std::signal(SIGPIPE, SIG_IGN);
    RunReviewServer(backend, options, [](const std::string& url) {
      fmt::print("asbuilt review: {}\n", url);
      std::fflush(stdout);
    });
  };
  // A home survey: its placement, corrected by moving rooms and saying
  // which doors are one (docs/home.md); each room is reviewed on its own
  // with `asbuilt review OUT/rooms/NAME/`.
  if (HomeReviewSession::IsHomeSurvey(out_dir)) {
    if (export_training) {
      throw InputError(out_dir, "",
                       "a home survey: export each room's review (asbuilt review OUT/rooms/NAME/ "
                       "--export-training)");
    }
    HomeReviewSession home = HomeReviewSession::Open(out_dir);
    serve(home);
    return 0;
  }
  ReviewSession session = ReviewSession::Open(out_dir);
  if (export_training) {
    const TrainingExample example = session.ExportTraining();
    fmt::print("{} views with labels from the corrected plan → {}\n", example.views, example.dir.string());
    return 0;
  }
  serve(session);
  return 0;
}

}  // namespace asbuilt::cli
