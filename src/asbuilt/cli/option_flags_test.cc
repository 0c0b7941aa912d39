// `asbuilt survey`, `plan` and `points` take every PlanOptions and
// FramePointsOptions field as a flag, generated from the field lists
// (cli/field_flags.h): nested names get their prefix, the older spellings
// stay as aliases of the same field, and bad values are usage errors naming
// the flag.

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/plan/plan_options.h"
#include "asbuilt/render/dataset_synth.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/train.h"
#include "asbuilt/stereo/frame_points_options.h"

namespace asbuilt::cli {
namespace {
using testing_util::RunAsbuilt;
using testing_util::RunResult;

std::set<std::string> HelpFlagsOf(const std::string& command) {
  RunResult r = RunAsbuilt(command + " --help");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  std::set<std::string> flags;
  std::regex flag("--[a-z][a-z0-9.-]*[a-z0-9]");
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), flag); it != std::sregex_iterator(); ++it) {
    flags.insert(it->str());
  }
  return flags;
}

// The flag of every field of `fields` under `prefix` ("plan." or "").
std::vector<std::string> FieldFlagNames(const std::vector<Field>& fields, const std::string& prefix) {
  std::vector<std::string> out;
  for (const Field& f : fields) {
    std::string flag = "--" + prefix + f.name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    out.push_back(flag);
  }
  return out;
}

void ExpectEveryFieldHasAFlag(const std::string& command, const std::vector<Field>& fields, const std::string& prefix) {
  const std::set<std::string> help = HelpFlagsOf(command);
  for (const std::string& flag : FieldFlagNames(fields, prefix)) {
    EXPECT_TRUE(help.contains(flag)) << command << " --help lacks " << flag;
  }
}

TEST(OptionFlags, SurveyHasAFlagForEveryPlanAndPointsField) {
  ExpectEveryFieldHasAFlag("survey", PlanOptionFields().Fields(), "plan.");
  ExpectEveryFieldHasAFlag("survey", FramePointsOptionFields().Fields(), "points.");
  const std::set<std::string> help = HelpFlagsOf("survey");
  for (const char* alias : {"--epsilon-m", "--dense-stride", "--contacts", "--snap-contacts-px"}) {
    EXPECT_TRUE(help.contains(alias)) << "survey --help lacks the alias " << alias;
  }
  EXPECT_TRUE(help.contains("--points.no-use-corners"));
  EXPECT_GT(PlanOptionFields().size() + FramePointsOptionFields().size(), 100u);
}

TEST(OptionFlags, PlanHasAFlagForEveryPlanField) { ExpectEveryFieldHasAFlag("plan", PlanOptionFields().Fields(), ""); }

TEST(OptionFlags, PointsHasAFlagForEveryPointsField) {
  ExpectEveryFieldHasAFlag("points", FramePointsOptionFields().Fields(), "");
}

// num_disparities_px = 24 passes the flag's bounds but not
// DisparityOptions::Check(), whose error names the nested field: so the flag
// reached it.
TEST(OptionFlags, NestedFlagSetsTheNestedField) {
  RunResult r = RunAsbuilt("survey missing.json -o /tmp/x --points.disparity.num-disparities-px 24");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("DisparityOptions.num_disparities_px = 24"), std::string::npos) << r.out;
}

TEST(OptionFlags, AliasAndItsNewNameSetTheSameField) {
  for (const char* flag : {"--disparity.num-disparities-px", "--num-disparities"}) {
    RunResult r = RunAsbuilt(std::string("points missing.json --use-capture-labels -o /tmp/x ") + flag + " 24");
    EXPECT_EQ(r.exit_code, 2) << flag << ": " << r.out;
    EXPECT_NE(r.out.find("DisparityOptions.num_disparities_px = 24"), std::string::npos) << flag << ": " << r.out;
  }
  for (const char* flag : {"--points.dense-stride-px", "--dense-stride"}) {
    RunResult r = RunAsbuilt(std::string("survey missing.json -o /tmp/x ") + flag + " 0");
    EXPECT_EQ(r.exit_code, 2) << flag << ": " << r.out;
    EXPECT_NE(r.out.find("--points.dense-stride-px: must be an integer >= 1, got 0"), std::string::npos)
        << flag << ": " << r.out;
  }
}

// `asbuilt ARGS` is a usage error (exit 2) whose message holds `text`.
void ExpectUsageError(const std::string& args, const std::string& text) {
  RunResult r = RunAsbuilt(args);
  EXPECT_EQ(r.exit_code, 2) << args << ": " << r.out;
  EXPECT_NE(r.out.find(text), std::string::npos) << args << ": " << r.out;
}

TEST(OptionFlags, BadNestedValueIsAUsageErrorNamingTheFlag) {
  ExpectUsageError("survey missing.json -o /tmp/x --plan.epsilon-m -1", "--plan.epsilon-m: must be > 0, got -1");
  ExpectUsageError("survey missing.json -o /tmp/x --points.contacts sometimes",
                   "--points.contacts: must be one of \"auto\", \"always\", \"off\"");
  ExpectUsageError("points missing.json --use-capture-labels -o /tmp/x --disparity.block-size-px 0",
                   "--disparity.block-size-px: must be an integer >= 1 and <= 255, got 0");
}

std::vector<Field> Without(std::vector<Field> fields, const std::set<std::string>& names) {
  std::erase_if(fields, [&](const Field& f) { return names.contains(f.name); });
  return fields;
}

void ExpectAliases(const std::string& command, std::initializer_list<const char*> aliases) {
  const std::set<std::string> help = HelpFlagsOf(command);
  for (const char* alias : aliases) EXPECT_TRUE(help.contains(alias)) << command << " --help lacks " << alias;
}

TEST(OptionFlags, TrainAndExperimentHaveAFlagForEveryTrainingField) {
  ExpectEveryFieldHasAFlag("train", TrainOptionFields().Fields(), "");
  ExpectAliases("train", {"--batch", "--warmup", "--drop-path", "--val-max", "--stop-after", "--dist-timeout",
                          "--scale", "--crop", "--ratio-min", "--ratio-max", "--no-flip", "--no-photometric",
                          "--no-blur-noise", "--stray-light", "--augment.no-flip"});
  ExpectEveryFieldHasAFlag(
      "experiment ratios",
      Without(TrainOptionFields().Fields(), {"seed", "val_fraction", "stop_after_epoch", "dist_timeout_s"}), "");
  ExpectAliases("experiment ratios", {"--batch", "--scale", "--crop", "--seed"});
}

TEST(OptionFlags, DatasetAndClusterSynthHaveAFlagForEveryItemField) {
  for (const char* command : {"dataset synth", "cluster synth"}) {
    ExpectEveryFieldHasAFlag(command, DatasetSynthOptionFields().Fields(), "");
    ExpectAliases(command, {"--size", "--spp", "--effects", "--rig-share", "--no-indirect", "--photo-dir"});
  }
}

TEST(OptionFlags, PanoramaViewsAreTheSameFlagsWhereverTheyAreTaken) {
  for (const char* command : {"pano views", "eval zind"}) {
    ExpectEveryFieldHasAFlag(command, TurnInPlaceOptionFields().Fields(), "");
    ExpectAliases(command, {"--size", "--pano-size", "--pano-fx", "--pano-views", "--yaw-step", "--pano-yaw-step",
                            "--first-yaw", "--pitch"});
  }
  ExpectEveryFieldHasAFlag("survey", TurnInPlaceOptionFields().Fields(), "pano.");
  ExpectAliases("survey", {"--pano-size", "--pano-fx", "--pano-views", "--pano-yaw-step"});
}

TEST(OptionFlags, SegmentingCommandsTakeTheSegmentOptions) {
  for (const char* command : {"segment", "eval seg"}) {
    ExpectEveryFieldHasAFlag(command, SegmentOptionFields().Fields(), "");
    ExpectAliases(command, {"--scale", "--batch"});
  }
  ExpectEveryFieldHasAFlag("eval zind", Without(SegmentOptionFields().Fields(), {"batch_size"}), "");
  ExpectAliases("eval zind", {"--seg-scale"});
}

TEST(OptionFlags, ASizeFlagAndItsFieldsFlagsTogetherAreAUsageError) {
  ExpectUsageError("pano views missing.png -o /tmp/x --size 64x32 --width-px 64", "not both");
  ExpectUsageError("pano views missing.png -o /tmp/x --size 40000x20",
                   "--size (its --width-px): must be an integer >= 1 and <= 32768, got 40000");
}

TEST(OptionFlags, AnUnknownLeverNamesIt) {
  RunResult r = RunAsbuilt("dataset synth -o /tmp/asbuilt_no_synth --count 1 --levers sunlight,moonlight");
  EXPECT_NE(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("moonlight"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists("/tmp/asbuilt_no_synth/synth.json"));
}

}  // namespace
}  // namespace asbuilt::cli
