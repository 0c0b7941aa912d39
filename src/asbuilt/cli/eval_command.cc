// `asbuilt eval <what> …` — scores results against the truth. Each kind of
// evaluation is one CLI11 subcommand:
//   eval plan PLAN TRUTH [--json FILE]   floor plan vs truth.json (plan/score.h)

#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/score.h"
#include "asbuilt/util/file.h"

namespace asbuilt::cli {

int RunEvalCommand(int argc, char** argv) {
  CLI::App app("Score results against the truth.", "asbuilt eval");
  AddCommonFlags(app);
  app.require_subcommand(1);

  // eval plan
  CLI::App* plan_cmd = app.add_subcommand(
      "plan",
      "score a floor plan against the truth: wall recall/precision and length error, opening\n"
      "recall/precision per kind and width error, room area error (table on stdout)");
  std::string plan_path, truth_path, plan_json_out;
  ScoreOptions score_options;
  plan_cmd->add_option("plan", plan_path, "predicted plan.json")->required();
  plan_cmd->add_option("truth", truth_path, "truth.json")->required();
  plan_cmd->add_option("--json", plan_json_out, "also write the scores as JSON to FILE");
  plan_cmd->add_option("--wall-max-angle-deg", score_options.wall_max_angle_deg,
                       "max angle between matched walls")->capture_default_str();
  plan_cmd->add_option("--wall-max-distance-m", score_options.wall_max_distance_m,
                       "max mean endpoint-to-line distance of matched walls")->capture_default_str();
  plan_cmd->add_option("--opening-max-centre-distance-m", score_options.opening_max_centre_distance_m,
                       "max distance between matched opening centres")->capture_default_str();

  Parse(app, argc, argv);

  if (plan_cmd->parsed()) {
    Plan predicted = ReadPlan(plan_path);
    Plan truth = ReadPlan(truth_path);
    PlanScore score = ScorePlan(predicted, truth, score_options);
    if (!plan_json_out.empty()) WriteFileAtomic(plan_json_out, PlanScoreToJson(score).dump(1) + "\n");
    fmt::print("{}", score.Table());
    return 0;
  }
  return 0;
}

}  // namespace asbuilt::cli
