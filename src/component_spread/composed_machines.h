#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "solver/signal.h"

namespace gearpatch::verify {
struct VerifyResult;
}

namespace gearpatch::component_spread {

/// How a changed deck departs from the perfect deck's trace of one signal,
/// at each of the perfect deck's times: the shortest time shift of the
/// perfect trace (within ± verify's time tolerance) that comes closest to the
/// changed trace's value, and what remains beyond that shift. Shifts of
/// several components add as shifts, so an impact two offsets each move a
/// little lands where both move it, not as two half-impacts.
struct Departure {
  std::vector<double> shift;   ///< s: the changed trace's value is the perfect trace's at t − shift
  std::vector<double> excess;  ///< the signal's unit, beyond the shifted perfect trace
};
using Departures = std::map<Signal, Departure>;

/// How one component moves each signal's trace, measured with ngspice at a
/// few of its values, 0 among them (no departure). Between measured values
/// the departure is interpolated linearly in the component's value, past
/// the ends continued by the last segment, so an effect that grows faster
/// than linearly (an impact or a lock that an offset past a threshold
/// changes) is followed where it was measured.
struct ComponentResponse {
  std::string component;              ///< as the budget's shares name it
  std::vector<double> values;         ///< ascending, 0 among them
  std::vector<Departures> departure;  ///< per value
  /// Its departure is an event (it saturates, or appears past a threshold,
  /// between two measured sizes), not a change in proportion to its value.
  bool event = false;
};

/// What virtual machines are composed from without running them: the
/// perfect deck's traces, the reference tube's range at each of their times
/// (the reference's lowest and highest value within ± verify's time
/// tolerance), each signal's full scale and each component's response.
struct TraceModel {
  std::vector<double> t;
  std::map<Signal, std::vector<double>> perfect, low, high;
  std::map<Signal, double> full_scale;
  std::map<Signal, double> width;  ///< the tube's half-width in value: the tolerance of full scale
  double shift = 0;                ///< s, the tube's half-width in time: verify's time tolerance
  std::vector<ComponentResponse> components;
};

/// The perfect deck's run as a model with no component yet: its traces, and
/// the tube of its reference as verify's comparison builds it.
TraceModel trace_model(const verify::VerifyResult& perfect);

/// How `variant` departs from the model's perfect traces, each signal on
/// the perfect deck's time grid.
Departures departures(const TraceModel& model, const verify::VerifyResult& variant);

/// Adds a component measured at `values` (any order, 0 excluded) with its departures.
void add_component(TraceModel& model, const std::string& component, std::vector<double> values,
                   std::vector<Departures> departures);

/// Each signal's amplitude error (verify's tube measure, fraction of full
/// scale) of the machine whose components take `values` (one per
/// model.components, in order): the perfect trace shifted by the
/// components' interpolated shifts plus their excesses, its largest distance
/// outside the reference's range. Proportional components' shifts and
/// excesses add; the events' count once: at each point, per direction, the
/// farthest of them.
std::map<Signal, double> composed_errors(const TraceModel& model, const std::vector<double>& values);

/// The p90 over many composed machines: per signal, and of each machine's worst signal.
struct ComposedP90 {
  std::map<Signal, double> signals;
  double worst = 0;
  std::size_t machines = 0;
};

/// Composes each machine (values per component, as composed_errors) and
/// takes the p90 of each signal's error and of the worst signal's.
ComposedP90 composed_p90(const TraceModel& model, const std::vector<std::vector<double>>& machines);

}  // namespace gearpatch::component_spread
