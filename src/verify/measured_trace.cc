#include "verify/measured_trace.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "common/error.h"
#include "verify/trace_smoothing.h"

namespace gearpatch::verify {
namespace {

Signal signal_named(const std::string& name, const std::string& option) {
  for (Signal s : all_signals)
    if (to_string(s) == name) return s;
  throw Error(fmt::format("{}: '{}' is not a signal: one of omega_p, omega_s, dphi, m0", option, name));
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// The step between the distinct values a column takes: an 8-bit scope's
/// quantum (the median gap, so that a value printed to three digits still
/// reads as its step); a computed or averaged column's is tiny.
double quantisation_step(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const double span = v.back() - v.front();
  std::vector<double> gaps;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (const double d = v[i] - v[i - 1]; d > 1e-9 * std::max(span, 1e-12)) gaps.push_back(d);
  return gaps.empty() ? 0 : median(gaps);
}

/// rms about the median of the samples before `end`.
double noise(const std::vector<double>& v, std::size_t end) {
  if (end < 5) return 0;
  const std::vector<double> head(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(end));
  const double m = median(head);
  double sum = 0;
  for (double x : head) sum += (x - m) * (x - m);
  return std::sqrt(sum / static_cast<double>(end));
}

/// Where one channel leaves its initial level, back along its first slope; none if it never does.
std::optional<double> departure(const std::vector<double>& t, const std::vector<double>& y, double unit_volts,
                                const std::string& path) {
  const std::size_t held = std::max<std::size_t>(5, t.size() / 50);
  if (t.size() < 2 * held) return std::nullopt;
  const std::vector<double> head(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(held));
  const double level = median(head);
  const double threshold = std::max({6 * noise(y, held), 1.5 * quantisation_step(y), 0.005 * unit_volts});
  std::size_t i = 1;
  while (i + 1 < y.size() && !(std::abs(y[i] - level) > threshold && std::abs(y[i + 1] - level) > threshold)) ++i;
  if (i + 1 >= y.size()) return std::nullopt;
  if (i < held)
    throw Error(fmt::format("{}: a channel leaves its initial level at t = {:.6g} s, within the first {} samples: "
                            "the recording begins after the run started; give --start T",
                            path, t[i], held));
  // Least squares through the samples from the threshold to 6 thresholds away,
  // however densely recorded (a fixed count of a deep record spans less than
  // a step, and its slope is the noise's), within a twentieth of the record.
  const std::size_t most = std::max<std::size_t>(20, y.size() / 20);
  double st = 0, sy = 0, stt = 0, sty = 0;
  std::size_t n = 0;
  for (std::size_t j = i; j < y.size() && n < most && (n < 2 || std::abs(y[j] - level) < 6 * threshold); ++j, ++n)
    st += t[j], sy += y[j], stt += t[j] * t[j], sty += t[j] * y[j];
  const double slope = (n * sty - st * sy) / (n * stt - st * st);
  const double at_i = sy / n + slope * (t[i] - st / n);
  // Back along the slope by at most twice the fit's own span: a jump (two
  // samples at one level past the threshold) has no slope to follow.
  const double back = (at_i - level) / slope, span = t[i + n - 1] - t[i];
  const double start = t[i] - (std::isfinite(back) ? std::clamp(back, 0.0, 2 * span) : 0.0);
  return std::max(start, t[held - 1]);  // the level held over the first samples
}

}  // namespace

double MeasuredTrace::worst_resolution() const {
  double worst = 0;
  for (const auto& r : resolution) worst = std::max(worst, r.fraction);
  return worst;
}

ChannelReading parse_channel_reading(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq + 1 >= text.size())
    throw Error(fmt::format("--channel {}: write SIGNAL=COLUMN, e.g. omega_p=CH1 (or omega_p=-CH1 for the "
                            "inverted output)", text));
  ChannelReading r{signal_named(text.substr(0, eq), "--channel " + text), text.substr(eq + 1), 1};
  if (r.channel.front() == '-') r.sign = -1, r.channel.erase(0, 1);
  if (r.channel.empty()) throw Error(fmt::format("--channel {}: no column after the sign", text));
  r.channel = canonical_channel(r.channel);
  return r;
}

std::pair<std::string, double> parse_channel_number(const std::string& option, const std::string& text) {
  const auto eq = text.find('=');
  double x = 0;
  const char* from = eq == std::string::npos ? nullptr : text.data() + eq + 1;
  if (!from || std::from_chars(from, text.data() + text.size(), x).ptr != text.data() + text.size() ||
      !std::isfinite(x) || (option == "--probe" && x <= 0))
    throw Error(fmt::format("{} {}: write CHANNEL=NUMBER, e.g. CH1={}", option, text,
                            option == "--probe" ? "10 (positive)" : "0.05 (volts)"));
  return {canonical_channel(text.substr(0, eq)), x};
}

double find_run_start(const std::vector<double>& t, const std::vector<std::vector<double>>& volts, double unit_volts,
                      const std::string& path) {
  std::optional<double> start;
  for (const auto& y : volts)
    if (const auto d = departure(t, y, unit_volts, path); d && (!start || *d < *start)) start = d;
  if (!start)
    throw Error(fmt::format("{}: no channel leaves the level it holds at the recording's start (IC): the run's "
                            "start cannot be found; give --start T (scope seconds)", path));
  return *start;
}

namespace {

/// The readings: --channel ones first, then the watch list's for the signals they leave.
std::vector<ChannelReading> readings_of(const MeasuredOptions& o, const std::vector<WatchedSignal>& watch) {
  std::vector<ChannelReading> out = o.channels;
  for (const WatchedSignal& w : watch)
    if (std::none_of(out.begin(), out.end(), [&](const ChannelReading& r) { return r.signal == w.signal; }))
      out.push_back({w.signal, w.channel, w.sign});
  return out;
}

/// A channel's probe ratio or offset: the option's, else the file's, else
/// `otherwise`; `said` gets where it came from ("" for neither).
double channel_setting(const std::map<std::string, double>& option, const std::map<std::string, double>& file,
                       const std::string& channel, double otherwise, const std::string& option_name,
                       std::string& said) {
  said = "";
  for (const auto& [map, name] : {std::pair{&option, option_name}, std::pair{&file, std::string("the file")}})
    if (const auto it = map->find(channel); it != map->end()) {
      said = name;
      return it->second;
    }
  return otherwise;
}

/// "probe x10 (the file), offset 0.05 V (--offset)" for what was applied to a column, or "".
std::string settings_note(double probe, const std::string& probe_from, double offset, const std::string& offset_from) {
  std::string note;
  if (!probe_from.empty()) note = fmt::format("probe x{:g} ({})", probe, probe_from);
  if (!offset_from.empty()) note += fmt::format("{}offset {:g} V ({})", note.empty() ? "" : ", ", offset, offset_from);
  return note;
}

/// Each recorded column's worst excursion beyond ±1 machine unit, its steps and noise allowed.
std::vector<Overload> recorded_overloads(const MeasuredTrace& m) {
  std::vector<Overload> out;
  for (const ChannelReading& r : m.readings) {
    const auto& mu = m.machine_units.at(r.signal);
    Overload worst{r.channel + " (" + to_string(r.signal) + ")", 0, 0};
    for (std::size_t i = 0; i < m.trace.t.size(); ++i)
      if (std::abs(mu[i]) > std::abs(worst.value)) worst.t = m.trace.t[i], worst.value = mu[i];
    // A recording's steps and noise reach a little beyond a signal that touches 1 MU.
    const auto res = std::find_if(m.resolution.begin(), m.resolution.end(), [&](const auto& x) { return x.signal == r.signal; });
    if (std::abs(worst.value) > 1 + res->fraction + 1e-6) out.push_back(worst);
  }
  return out;
}

/// Smooths one column over `half` samples either side into `smoothed` and
/// states its resolution as recorded and as judged.
ChannelResolution smooth_channel(const ChannelReading& reading, const std::vector<double>& volts,
                                 std::vector<double>& smoothed, std::size_t before, std::size_t half, double unit) {
  ChannelResolution r{reading.signal, reading.channel, quantisation_step(volts), noise(volts, before)};
  r.recorded = r.fraction = std::max(r.step_volts, 2 * r.noise_volts) / unit;
  smoothed = volts;
  if (half < 1 || 2 * half + 1 > volts.size()) return r;
  smoothed = smooth_moving_average(volts, half);
  r.noise_volts = residual_noise(volts, smoothed, half);
  r.recorded = std::max(r.step_volts, 2 * r.noise_volts) / unit;
  r.smoothed_over = 2 * half + 1;
  // The noise before the steps (the residual holds the steps' own step²/12 too) dithers them.
  const double analog = std::sqrt(std::max(0.0, r.noise_volts * r.noise_volts - r.step_volts * r.step_volts / 12));
  r.fraction = std::max(2 * r.noise_volts * std::sqrt(smoothed_noise_gain(half)),
                        dithered_quantisation_bias(r.step_volts, analog)) / unit;
  return r;
}

/// The samples from the start on into machine units (all of them) and into
/// physical units and real time (up to the run's end): the smoothed columns
/// for the tube, the ones smoothed over half the window for the impacts.
void convert_samples(MeasuredTrace& m, const std::vector<double>& t, const circuit::Circuit& circuit,
                     const std::vector<std::vector<double>>& smoothed,
                     const std::vector<std::vector<double>>& impact_volts, std::size_t before, double duration) {
  const double unit = circuit.machine.unit_volts;
  const double end = m.start + circuit.beta * duration * (1 + 1e-9);
  for (std::size_t i = before; i < t.size(); ++i) {
    m.machine_t.push_back(t[i] - m.start);
    for (std::size_t k = 0; k < m.readings.size(); ++k)
      m.machine_units[m.readings[k].signal].push_back(m.readings[k].sign * smoothed[k][i] / unit);
    if (t[i] > end) continue;
    m.trace.t.push_back((t[i] - m.start) / circuit.beta);
    m.impact_trace.t.push_back(m.trace.t.back());
    for (std::size_t k = 0; k < m.readings.size(); ++k) {
      const Signal s = m.readings[k].signal;
      const double physical = m.readings[k].sign / unit * circuit.probes.at(s).full_scale;
      m.trace.signals[s].push_back(physical * smoothed[k][i]);
      m.impact_trace.signals[s].push_back(physical * impact_volts[k][i]);
    }
  }
}

}  // namespace

MeasuredTrace measure_trace(const ScopeRecording& rec, const MeasuredOptions& o, const circuit::Circuit& circuit,
                            const std::vector<WatchedSignal>& watch, double duration, double smoothing) {
  MeasuredTrace m;
  m.format = rec.format, m.time_from = rec.time_from, m.samples = rec.t.size();
  const double unit = circuit.machine.unit_volts;
  std::vector<std::vector<double>> machine_volts;  // per reading, sign not yet applied
  for (const ChannelReading& r : readings_of(o, watch)) {
    const ScopeColumn* column = rec.find(r.channel);
    if (!column) {
      m.missing.push_back(r.signal);
      continue;
    }
    std::string probe_from, offset_from;
    const double probe = channel_setting(o.probe, rec.probe, column->channel, 1, "--probe", probe_from);
    const double offset = channel_setting(o.offset, rec.offset, column->channel, 0, "--offset", offset_from);
    std::vector<double> v = column->volts;
    for (double& x : v) x = probe * x - offset;
    if (const std::string note = settings_note(probe, probe_from, offset, offset_from); !note.empty())
      m.applied[r.signal] = note;
    m.readings.push_back({r.signal, column->channel, r.sign});
    machine_volts.push_back(std::move(v));
  }
  for (const auto& [option, values] : {std::pair{"--probe", &o.probe}, std::pair{"--offset", &o.offset}})
    for (const auto& entry : *values)
      if (!rec.find(entry.first))
        throw Error(fmt::format("{} {}: {} has no such column", option, entry.first, o.path));
  if (m.readings.empty()) {
    std::string names;
    for (const ScopeColumn& c : rec.columns) names += (names.empty() ? "" : ", ") + c.channel;
    throw Error(fmt::format("{}: none of the watched channels is recorded (the file has {}); map them with "
                            "--channel SIGNAL=COLUMN", o.path, names));
  }
  m.start_given = o.start.has_value();
  m.start = o.start ? *o.start : find_run_start(rec.t, machine_volts, unit, o.path);
  const std::size_t before = static_cast<std::size_t>(std::lower_bound(rec.t.begin(), rec.t.end(), m.start) - rec.t.begin());
  const double interval = (rec.t.back() - rec.t.front()) / static_cast<double>(rec.t.size() - 1);
  const auto half = static_cast<std::size_t>(std::max(0.0, std::floor(smoothing * circuit.beta / interval)));
  std::vector<std::vector<double>> smoothed(m.readings.size()), impact_volts(m.readings.size());
  for (std::size_t k = 0; k < m.readings.size(); ++k) {
    m.resolution.push_back(smooth_channel(m.readings[k], machine_volts[k], smoothed[k], before, half, unit));
    impact_volts[k] = smooth_moving_average(machine_volts[k], half / 2);
  }
  convert_samples(m, rec.t, circuit, smoothed, impact_volts, before, duration);
  if (m.trace.t.size() < 2)
    throw Error(fmt::format("{}: fewer than two samples between the run's start (t = {:.6g} s) and its end", o.path,
                            m.start));
  m.span = m.trace.t.back();
  m.overloads = recorded_overloads(m);
  return m;
}

}  // namespace gearpatch::verify
