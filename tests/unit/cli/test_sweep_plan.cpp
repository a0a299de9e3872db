// SPDX-License-Identifier: Apache-2.0
// gnssemu sweep: sweep-file parsing, plan expansion, task ids, hashes, the
// tables' CSV, Slurm's array specs and job states (docs/sweep.md).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/error.hpp"
#include "tools/gnssemu/batch/truth_csv.hpp"
#include "tools/gnssemu/sweep/collect/csv_row.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"
#include "tools/gnssemu/sweep/plan/sweep_file.hpp"
#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"
#include "tools/gnssemu/sweep/plan/truth_generator.hpp"
#include "tools/gnssemu/sweep/run/slurm_executor.hpp"
#include "tools/gnssemu/sweep/run/sweep_task.hpp"
#include "tools/gnssemu/sweep/run/task_state.hpp"

namespace gnssemu::cli::sweep {
namespace {

namespace fs = std::filesystem;

const std::string kGen =
    R"({ generator = "line", name = "still", week = 2190, tow_s = 522000, duration_s = 20, lat_deg = 48.8738, lon_deg = 2.295, height_m = 100 })";

class SweepPlanTest : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gnssemu-sweep-unit-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    write("base.toml", "[origin]\nlat_deg = 48.8738\nlon_deg = 2.2950\nheight_m = 100.0\n\n[nav]\nfile = \"" +
                           std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n\"\n\n[receiver]\nrate_hz = 1.0\n");
    write("a.csv", "gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,522000,48.8738,2.295,100\n2190,522010,48.8738,2.295,100\n");
    write("s.toml", "[[event]]\ntype = \"outage\"\nstart_s = 5\nduration_s = 5\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  SweepSpec parse(const std::string& text) { return parse_sweep(text, "sweep.toml", dir_.string()); }
  /// The error's text, or "" when it parsed.
  std::string error_of(const std::string& text) {
    try {
      make_plan(parse(text));
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(SweepPlanTest, ProductInFileOrderLastAxisFastest) {
  const Plan p = make_plan(parse("config = \"base.toml\"\n[axes]\ntruth = \"a.csv\"\nseed = { from = 1, to = 3 }\n"
                                 "start_h = [0, 12]\n\"receiver.profile\" = [\"ublox_m8\", \"geodetic\"]\n"));
  ASSERT_EQ(p.tasks.size(), 12u);
  EXPECT_EQ(p.axis_keys, (std::vector<std::string>{"truth", "seed", "start_h", "receiver.profile"}));
  EXPECT_EQ(p.tasks[0].values[1], "1");
  EXPECT_EQ(p.tasks[0].values[3], "ublox_m8");
  EXPECT_EQ(p.tasks[1].values[3], "geodetic");
  EXPECT_EQ(p.tasks[2].values[2], "12");
  EXPECT_EQ(p.tasks[11].values[1], "3");
  for (std::size_t i = 0; i < p.tasks.size(); ++i) EXPECT_EQ(p.tasks[i].id, static_cast<int>(i));
  EXPECT_EQ(p.tasks[0].truth_hash, file_hash((dir_ / "a.csv").string()));
  EXPECT_EQ(p.tasks[0].config_hash, file_hash((dir_ / "base.toml").string()));
  EXPECT_EQ(p.tasks[0].scenario_hash, "");
  EXPECT_EQ(p.overrides(p.tasks[1]),
            (std::vector<Override>{{"receiver.seed", "1"}, {"receiver.profile", "geodetic"}}));
}

TEST_F(SweepPlanTest, CasesAreProductsOverTheAxes) {
  const Plan p = make_plan(parse("config = \"base.toml\"\n[axes]\ntruth = \"a.csv\"\nseed = [1, 2]\n"
                                 "[[case]]\nscenario = \"none\"\nseed = 1\n"
                                 "[[case]]\nscenario = \"s.toml\"\n"));
  ASSERT_EQ(p.tasks.size(), 3u);
  EXPECT_EQ(p.value(p.tasks[0], "scenario"), "none");
  EXPECT_EQ(p.value(p.tasks[2], "seed"), "2");
  EXPECT_EQ(p.tasks[2].scenario_hash, file_hash((dir_ / "s.toml").string()));
}

TEST_F(SweepPlanTest, SamePlanSameHashAndCsv) {
  const std::string text = "config = \"base.toml\"\n[axes]\ntruth = [\"a.csv\", " + kGen + "]\nseed = [4, 5]\n";
  const Plan a = make_plan(parse(text)), b = make_plan(parse(text));
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(tasks_csv_text(a), tasks_csv_text(b));
  write_plan(a, (dir_ / "out").string());
  const Plan back = read_plan((dir_ / "out").string());
  EXPECT_EQ(back.hash, a.hash);
  EXPECT_EQ(back.value(back.tasks[2], "truth"), a.value(a.tasks[2], "truth"));
  const Plan other = make_plan(parse("config = \"base.toml\"\n[axes]\ntruth = \"a.csv\"\nseed = [6]\n"));
  EXPECT_NE(other.hash, a.hash);
  write_plan(a, (dir_ / "out").string());  // the same plan again: fine
  fs::create_directories(dir_ / "out" / "tasks" / "0");
  EXPECT_THROW(write_plan(other, (dir_ / "out").string()), Error);
}

TEST_F(SweepPlanTest, BadInputIsFileLineError) {
  const std::string head = "config = \"base.toml\"\n[axes]\ntruth = \"a.csv\"\n";
  EXPECT_NE(error_of(head + "speed = [1]\n").find("sweep.toml:4: unknown axis key 'speed'"), std::string::npos);
  EXPECT_NE(error_of(head + "seed = []\n").find("sweep.toml:4: axis 'seed' has no values"), std::string::npos);
  EXPECT_NE(error_of(head + "seed = { from = 5, to = 1 }\n").find("sweep.toml:4:"), std::string::npos);
  EXPECT_NE(error_of(head + "scenario = \"nope.toml\"\n").find("sweep.toml:4: scenario file not found"),
            std::string::npos);
  EXPECT_NE(error_of("config = \"base.toml\"\n[axes]\ntruth = \"b.csv\"\n").find("sweep.toml:3: truth file not found"),
            std::string::npos);
  EXPECT_NE(error_of(head + "\"receiver.nonsense\" = [1]\n").find("sweep.toml:4: receiver.nonsense = 1:"),
            std::string::npos);
  EXPECT_NE(error_of(head + "[[case]]\nseed = 1\n[[case]]\nseed = 1\n").find("sweep.toml:6: duplicate task"),
            std::string::npos);
  EXPECT_NE(error_of("config = \"base.toml\"\njobs = 3\n[axes]\ntruth = \"a.csv\"\n").find("sweep.toml:2: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("config = \"base.toml\"\n[axes]\nseed = [1]\n").find("no truth"), std::string::npos);
  EXPECT_NE(error_of("config = \"base.toml\"\n").find("the product would be empty"), std::string::npos);
  EXPECT_NE(error_of("config = \"base.toml\"\n[axes]\ntruth = [{ generator = \"line\", name = \"x\" }]\n")
                .find("sweep.toml:3: truth generator: 'week' is required"),
            std::string::npos);
}

TEST(SweepExamples, ShippedSweepFilesPlan) {
  const fs::path dir = fs::path(GNSSEMU_SOURCE_DIR) / "config" / "examples" / "sweeps";
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".toml" || e.path().filename() == "base.toml") continue;
    ++files;
    SCOPED_TRACE(e.path().string());
    EXPECT_NO_THROW(make_plan(read_sweep_file(e.path().string())));
  }
  EXPECT_GE(files, 4);
  EXPECT_EQ(make_plan(read_sweep_file((dir / "jamming.toml").string())).tasks.size(), 160u);
}

TEST(SweepCsv, QuotedCellsRoundTrip) {
  const std::vector<std::string> cells{"0", "{ a = \"b\", c = 1 }", "plain", ""};
  const std::string row = csv_row(cells);
  EXPECT_EQ(row, "0,\"{ a = \"\"b\"\", c = 1 }\",plain,\n");
  EXPECT_EQ(split_csv_row(row.substr(0, row.size() - 1), "t", 1), cells);
  EXPECT_THROW(split_csv_row("a,\"b", "t", 1), Error);
}

TEST(SweepTruth, GeneratedAndShiftedTruthReadsBack) {
  const TruthGenerator g = parse_generator(
      R"({ generator = "line", name = "d", week = 2190, tow_s = 520000, duration_s = 10, lat_deg = 48, lon_deg = 2, speed_m_s = 10, heading_deg = 90 })",
      "t", 1);
  std::vector<world::TruthSample> s = generate_truth(g);
  ASSERT_EQ(s.size(), 11u);
  EXPECT_NEAR((s[10].pos_m - s[0].pos_m).norm(), 100.0, 1e-6);
  shift_to_hour(s, 6.0);
  EXPECT_EQ(s[0].t.week(), 2190);
  EXPECT_DOUBLE_EQ(s[0].t.tow_s(), 518400.0 + 6 * 3600.0);
  std::istringstream in(truth_csv_text(s));
  const std::vector<world::TruthSample> back = read_truth_csv(in, "t");
  ASSERT_EQ(back.size(), s.size());
  EXPECT_LT((back[7].pos_m - s[7].pos_m).norm(), 1e-3);
  EXPECT_LT((back[7].vel_m_s - s[7].vel_m_s).norm(), 1e-3);
}

TEST(SweepSlurm, ArraySpecsAndJobStates) {
  EXPECT_EQ(array_spec({0, 1, 2, 3}, 0), "0-3");
  EXPECT_EQ(array_spec({3, 7, 8, 9, 12}, 2), "3,7-9,12%2");
  SlurmOptions o;
  o.gnssemu = "/opt/gnssemu";
  o.array_limit = 4;
  o.time = "5";
  const std::string one = sbatch_script("/d", {0, 1, 2}, o);
  EXPECT_NE(one.find("#SBATCH --array=0-2%4\n"), std::string::npos);
  EXPECT_NE(one.find("#SBATCH --output=/d/tasks/%a/task.log\n"), std::string::npos);
  EXPECT_NE(one.find("#SBATCH --time=5\n"), std::string::npos);
  EXPECT_NE(one.find("exec /opt/gnssemu sweep task /d \"$SLURM_ARRAY_TASK_ID\"\n"), std::string::npos);
  o.per_element = 2;
  const std::string packed = sbatch_script("/d", {0, 1, 2}, o, "/d/slurm/array-0.ids");
  EXPECT_NE(packed.find("#SBATCH --array=0-1%4\n"), std::string::npos);
  EXPECT_NE(packed.find("#SBATCH --output=/d/slurm/array-0-%a.log\n"), std::string::npos);
  const SchedulerStates s = parse_scontrol(
      "JobId=5 ArrayJobId=4 ArrayTaskId=1 JobName=x JobState=COMPLETED Reason=None ExitCode=0:0\n"
      "JobId=6 ArrayJobId=4 ArrayTaskId=3 JobName=x JobState=TIMEOUT Reason=TimeLimit ExitCode=0:15\n"
      "JobId=7 ArrayJobId=4 ArrayTaskId=0 JobName=x JobState=RUNNING Reason=None ExitCode=0:0\n"
      "JobId=4 ArrayJobId=4 ArrayTaskId=4-6%2 JobName=x JobState=PENDING Reason=JobArrayTaskLimit ExitCode=0:0\n");
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(s.at(0).state, TaskState::kRunning);
  EXPECT_EQ(s.at(3).state, TaskState::kFailed);
  EXPECT_NE(s.at(3).detail.find("TIMEOUT"), std::string::npos);
  EXPECT_EQ(s.at(5).state, TaskState::kPending);
  // Completed without a summary is a failure: the files, not the exit code, say done.
  EXPECT_EQ(s.at(1).state, TaskState::kFailed);
}

TEST_F(SweepPlanTest, TaskRunsAndSummarises) {
  const Plan p = make_plan(parse("config = \"base.toml\"\noutputs = [\"errors\"]\n[axes]\ntruth = [" + kGen +
                                 "]\nscenario = \"s.toml\"\n"));
  const std::string out = (dir_ / "out").string();
  write_plan(p, out);
  std::ostringstream log;
  const TaskSummary s = run_task(p, out, 0, log);
  EXPECT_EQ(s.epochs, 21);
  EXPECT_GT(s.avail_3d, 0.5);
  EXPECT_GE(s.fix_lost_s, 0.0);  // the outage at 5 s
  EXPECT_LE(s.fix_lost_s, 4.0);
  EXPECT_TRUE(fs::is_regular_file(fs::path(task_dir(out, 0)) / "errors.csv"));
  const std::vector<TaskStatus> st = task_states(p, out);
  EXPECT_EQ(st[0].state, TaskState::kDone);
  EXPECT_EQ(state_counts(st), "tasks 1: done 1, failed 0, running 0, pending 0, missing 0");
  EXPECT_NE(reproduce_command(p, out, p.tasks[0]).find("--scenario "), std::string::npos);
  const fs::path log_path = fs::path(task_dir(out, 0)) / kLogFile;
  std::ofstream(log_path) << "";
  EXPECT_EQ(log_tail(out, 0, 3), "");
  std::ofstream(log_path) << "a\nb\nc\nd\n";
  EXPECT_EQ(log_tail(out, 0, 2), "c\nd");
  EXPECT_EQ(log_tail(out, 0, 9), "a\nb\nc\nd");
}

}  // namespace
}  // namespace gnssemu::cli::sweep
