#include "solver/signal.h"

#include "common/enum_table.h"

namespace gearpatch {
namespace {

/// The one table of the signals: identity, name and unit.
struct SignalName {
  Signal key;
  const char* name;
  const char* unit;
};
constexpr SignalName signal_table[] = {
    {Signal::omega_p, "omega_p", "rad/s"},
    {Signal::omega_s, "omega_s", "rad/s"},
    {Signal::dphi, "dphi", "rad"},
    {Signal::m0, "m0", "N·m"},
};

}  // namespace

std::string to_string(Signal signal) { return row_of(signal_table, signal).name; }
std::string unit(Signal signal) { return row_of(signal_table, signal).unit; }

double value(const Sample& s, Signal signal) {
  switch (signal) {
    case Signal::omega_p: return s.omega_p;
    case Signal::omega_s: return s.omega_s;
    case Signal::dphi: return s.dphi;
    case Signal::m0: return s.m0;
  }
  return 0;  // not reached
}

const Extremum& peak(const SignalPeaks& p, Signal signal) {
  switch (signal) {
    case Signal::omega_p: return p.omega_p;
    case Signal::omega_s: return p.omega_s;
    case Signal::dphi: return p.dphi;
    case Signal::m0: return p.m0;
  }
  return p.m0;  // not reached
}

}  // namespace gearpatch
