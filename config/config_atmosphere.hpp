#pragma once
// [atmosphere], [signal] and [receiver.corrections]: the world's propagation
// and signal models and the receiver's own corrections. Internal to the
// config module (config.cpp reads, config_writer.cpp writes).
#include <string>
#include <string_view>

#include "config/toml_reader.hpp"
#include "core/common/error.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/world/world_config.hpp"

namespace gnssemu::config::detail {

/// [atmosphere] and its sub-tables into w.atmosphere.
void read_atmosphere(TableReader& t, world::WorldConfig& w);
/// [signal] and its sub-tables into w.signal, its tracking thresholds into r.tracking.
void read_signal(TableReader& t, world::WorldConfig& w, receiver::ReceiverConfig& r);
/// [receiver.corrections] into r.solver (iono / tropo).
void read_corrections(TableReader& t, receiver::SolverConfig& s);
/// Keys of [receiver.errors] added by the signal model.
void read_thermal_model(TableReader& errors, world::ErrorModelConfig& e);

/// A Gauss–Markov table: sigma under sigma_key, and tau_s, with their core ranges.
void read_gauss_markov(TableReader& t, world::GaussMarkovConfig& gm, std::string_view sigma_key,
                       const gnssemu::Range& sigma, const gnssemu::Range& tau);

/// The reason of a core error without its "what: " prefix.
std::string reason_of(const Error& e);

/// Runs validate (a core validator); its gnssemu::Error is re-thrown at the
/// line of at (the table's header).
template <class Validate>
void validate_at(const TableReader& at, Validate&& validate) {
  try {
    validate();
  } catch (const Error& e) {
    throw Error(at.file(), at.line(), reason_of(e));
  }
}

/// Checks the assembled models the way the world and the receiver will
/// (e.g. antenna gains, thresholds); a failure is reported at the line of at
/// (the table's header).
void check_models(const TableReader& at, const world::WorldConfig& w, const receiver::ReceiverConfig& r);

/// TOML text of [receiver.corrections], [atmosphere...] and [signal...];
/// number(v) formats a float so it reads back exactly.
std::string corrections_toml(const receiver::SolverConfig& s, std::string (*number)(double));
std::string atmosphere_toml(const world::WorldConfig& w, std::string (*number)(double));
std::string signal_toml(const world::WorldConfig& w, const receiver::ReceiverConfig& r, std::string (*number)(double));
/// Value of [receiver.errors] thermal_model.
std::string thermal_model_name(world::ThermalModel m);

}  // namespace gnssemu::config::detail
