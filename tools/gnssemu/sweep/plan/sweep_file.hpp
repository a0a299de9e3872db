// SPDX-License-Identifier: Apache-2.0
#pragma once
// A sweep file (TOML, docs/sweep.md): the base config, what each task keeps,
// and the axes whose values combine into tasks: [axes] as a full product, or
// [[case]] tables, each a product of its own values over [axes].
#include <string>
#include <vector>

namespace gnssemu::cli::sweep {

/// One value of an axis as tasks.csv carries it: an absolute file path
/// (truth, scenario), an inline-table generator (truth), a number (seed,
/// start_h) or a config value (dotted keys: plain text for strings, TOML
/// otherwise).
struct AxisValue {
  std::string text;
  int line = 0;  ///< line in the sweep file
};

struct Axis {
  std::string key;  ///< truth, scenario, seed, start_h, or a dotted config key ("receiver.profile")
  std::vector<AxisValue> values;
  int line = 0;
};

/// The batch outputs a task keeps besides its summary (--errors, --nmea, --ubx).
struct TaskOutputs {
  bool errors = false, nmea = false, ubx = false;
};

struct SweepSpec {
  std::string path;         ///< the sweep file, absolute
  std::string config_path;  ///< base config, absolute
  TaskOutputs outputs;
  double hacc_k = 3.0;      ///< consistency test: error > k * hAcc (k in (0, 100])
  std::vector<Axis> axes;   ///< [axes], file order
  struct Case {
    int line = 0;
    std::vector<Axis> axes;
  };
  std::vector<Case> cases;  ///< [[case]] tables; none: the [axes] product
};

/// "none" as a scenario value: no fault stage.
inline constexpr const char* kNoScenario = "none";

/// Read and check a sweep file: unknown keys and axis keys, empty axes, bad
/// ranges, missing truth or scenario files and scenario syntax are
/// gnssemu::Error "file:line: reason". Config override keys are checked
/// later, when the plan applies them (sweep_plan).
SweepSpec read_sweep_file(const std::string& path);
/// Same from text; dir: folder relative paths resolve against.
SweepSpec parse_sweep(const std::string& text, const std::string& name, const std::string& dir);

/// True for the axis keys that are config overrides (contain a dot).
bool is_override_key(const std::string& key);

}  // namespace gnssemu::cli::sweep
