#include "asbuilt/seg/distributed.h"

#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
using ::testing::HasSubstr;

EnvironmentLookup Env(std::map<std::string, std::string> vars) {
  return [vars = std::move(vars)](const std::string& name) -> std::optional<std::string> {
    auto it = vars.find(name);
    if (it == vars.end()) return std::nullopt;
    return it->second;
  };
}

// The message of the InvalidArgument `f` throws ("" when it throws none).
template <class F>
std::string InvalidArgumentOf(F&& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(FirstHostOfHostlist, TakesTheFirstNumberOfEachBracketGroup) {
  EXPECT_EQ(FirstHostOfHostlist("node[01-04,07],gpu3"), "node01");
  EXPECT_EQ(FirstHostOfHostlist("node[07,01-04]"), "node07");
  EXPECT_EQ(FirstHostOfHostlist("gpu3,node[01-04]"), "gpu3");
  EXPECT_EQ(FirstHostOfHostlist("rack[2-3]-n[5-6]"), "rack2-n5");
  EXPECT_EQ(FirstHostOfHostlist("login"), "login");
  EXPECT_EQ(FirstHostOfHostlist("n[0009]"), "n0009");
  EXPECT_EQ(FirstHostOfHostlist("10.0.0.5"), "10.0.0.5");
}

TEST(FirstHostOfHostlist, RejectsMalformedListsNamingTheVariable) {
  EXPECT_THAT(InvalidArgumentOf([] { FirstHostOfHostlist("node[01-04", "SLURM_STEP_NODELIST"); }),
              HasSubstr("SLURM_STEP_NODELIST = 'node[01-04': '[' without ']'"));
  EXPECT_THAT(InvalidArgumentOf([] { FirstHostOfHostlist("node01]", "X"); }), HasSubstr("']' without '['"));
  EXPECT_THAT(InvalidArgumentOf([] { FirstHostOfHostlist("", "X"); }), HasSubstr("X = '': no host"));
  EXPECT_THAT(InvalidArgumentOf([] { FirstHostOfHostlist("a[[1]]", "X"); }), HasSubstr("nested"));
}

TEST(DistributedOptionsFromEnvironment, ReadsSlurm) {
  DistributedOptions d = DistributedOptionsFromEnvironment(Env({{"SLURM_PROCID", "3"},
                                                                {"SLURM_NTASKS", "4"},
                                                                {"SLURM_STEP_NODELIST", "node[01-04,07],gpu3"},
                                                                {"SLURM_JOB_NODELIST", "other[1-9]"},
                                                                {"SLURM_JOB_ID", "123457"},
                                                                {"SLURM_STEP_ID", "2"}}));
  EXPECT_EQ(d.rank, 3);
  EXPECT_EQ(d.world_size, 4);
  EXPECT_EQ(d.master_addr, "node01");
  EXPECT_EQ(d.master_port, 20000 + 1457 * 10 + 2);
  EXPECT_NO_THROW(d.Check());
}

TEST(DistributedOptionsFromEnvironment, FallsBackToTheJobNodeListAndStepZero) {
  DistributedOptions d = DistributedOptionsFromEnvironment(
      Env({{"SLURM_PROCID", "0"}, {"SLURM_NTASKS", "2"}, {"SLURM_JOB_NODELIST", "cn[7-8]"}, {"SLURM_JOB_ID", "42"}}));
  EXPECT_EQ(d.master_addr, "cn7");
  EXPECT_EQ(d.master_port, 20420);
}

TEST(DistributedOptionsFromEnvironment, TorchrunVariablesWinOverSlurm) {
  DistributedOptions d = DistributedOptionsFromEnvironment(Env({{"RANK", "1"},
                                                                {"WORLD_SIZE", "2"},
                                                                {"MASTER_ADDR", "127.0.0.1"},
                                                                {"MASTER_PORT", "29500"},
                                                                {"SLURM_PROCID", "5"},
                                                                {"SLURM_NTASKS", "8"},
                                                                {"SLURM_STEP_NODELIST", "node[01-04]"},
                                                                {"SLURM_JOB_ID", "7"}}));
  EXPECT_EQ(d.rank, 1);
  EXPECT_EQ(d.world_size, 2);
  EXPECT_EQ(d.master_addr, "127.0.0.1");
  EXPECT_EQ(d.master_port, 29500);
  // One at a time: MASTER_PORT alone overrides Slurm's port.
  d = DistributedOptionsFromEnvironment(Env({{"SLURM_PROCID", "0"},
                                             {"SLURM_NTASKS", "2"},
                                             {"SLURM_STEP_NODELIST", "a1"},
                                             {"SLURM_JOB_ID", "7"},
                                             {"MASTER_PORT", "31000"}}));
  EXPECT_EQ(d.master_addr, "a1");
  EXPECT_EQ(d.master_port, 31000);
}

TEST(DistributedOptionsFromEnvironment, WorldSizeOneNeedsNoAddress) {
  DistributedOptions d = DistributedOptionsFromEnvironment(Env({{"RANK", "0"}, {"WORLD_SIZE", "1"}}));
  EXPECT_FALSE(d.enabled());
  EXPECT_NO_THROW(d.Check());
}

TEST(DistributedOptionsFromEnvironment, RejectsMissingOrBadValuesNamingTheVariable) {
  EXPECT_THAT(InvalidArgumentOf([] { DistributedOptionsFromEnvironment(Env({})); }),
              HasSubstr("--distributed needs this process's rank"));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptionsFromEnvironment(Env({{"RANK", "0"}}));
              }),
              HasSubstr("WORLD_SIZE"));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptionsFromEnvironment(Env({{"RANK", "x"}, {"WORLD_SIZE", "2"}}));
              }),
              HasSubstr("RANK = 'x': not an integer"));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptionsFromEnvironment(Env({{"SLURM_PROCID", "4"}, {"SLURM_NTASKS", "4"}}));
              }),
              HasSubstr("SLURM_PROCID = 4: must be in [0, 3]"));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptionsFromEnvironment(Env({{"RANK", "0"}, {"WORLD_SIZE", "0"}}));
              }),
              HasSubstr("WORLD_SIZE = 0: must be in [1, "));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptionsFromEnvironment(
                    Env({{"RANK", "0"}, {"WORLD_SIZE", "2"}, {"MASTER_ADDR", "h"}, {"MASTER_PORT", "70000"}}));
              }),
              HasSubstr("MASTER_PORT = 70000: must be in [1, 65535]"));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptionsFromEnvironment(Env({{"RANK", "0"}, {"WORLD_SIZE", "2"}, {"MASTER_PORT", "1"}}));
              }),
              HasSubstr("MASTER_ADDR"));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptionsFromEnvironment(Env({{"RANK", "0"}, {"WORLD_SIZE", "2"}, {"MASTER_ADDR", "h"}}));
              }),
              HasSubstr("MASTER_PORT"));
  EXPECT_THAT(
      InvalidArgumentOf([] {
        DistributedOptionsFromEnvironment(Env(
            {{"SLURM_PROCID", "0"}, {"SLURM_NTASKS", "2"}, {"SLURM_JOB_NODELIST", "n[1-2"}, {"SLURM_JOB_ID", "1"}}));
      }),
      HasSubstr("SLURM_JOB_NODELIST = 'n[1-2'"));
}

TEST(DistributedOptions, DefaultsAreValidAndChecksNameTheField) {
  EXPECT_NO_THROW(DistributedOptions{}.Check());
  EXPECT_THAT(InvalidArgumentOf([] { DistributedOptions{.rank = 2, .world_size = 2}.Check(); }),
              HasSubstr("DistributedOptions.rank = 2, must be in [0, 1]"));
  EXPECT_THAT(InvalidArgumentOf([] {
                DistributedOptions{.world_size = 2, .master_addr = "h", .master_port = 1, .timeout_s = 0}.Check();
              }),
              HasSubstr("DistributedOptions.timeout_s = 0"));
  EXPECT_THAT(InvalidArgumentOf([] { DistributedOptions{.world_size = 2, .master_port = 5}.Check(); }),
              HasSubstr("master_addr is empty"));
}

TEST(DistributedOptions, PrintsItself) {
  DistributedOptions d{.rank = 1, .world_size = 2, .master_addr = "n1", .master_port = 29500, .timeout_s = 60};
  EXPECT_EQ(d.ToJson().dump(), R"({"master_addr":"n1","master_port":29500,"rank":1,"timeout_s":60.0,"world_size":2})");
}

}  // namespace
}  // namespace asbuilt
