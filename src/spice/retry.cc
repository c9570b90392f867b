#include "spice/retry.h"

#include "common/error.h"

namespace gearpatch::spice {

Vectors run_with_retry(Simulator& simulator, const std::string& deck, const RunLimits& limits,
                       const std::function<std::optional<std::string>()>& fallback, const std::string& change,
                       std::optional<Retry>& retry) {
  std::string first;
  try {
    return simulator.run(deck, limits);
  } catch (const Error& e) {
    if (e.kind() != Error::Kind::simulator || !e.is_numerical_abort()) throw;
    first = e.what();
  }
  const std::optional<std::string> second = fallback();
  if (!second) throw Error(first, Error::Kind::simulator);
  try {
    Vectors v = simulator.run(*second, limits);
    retry = Retry{first, change};
    return v;
  } catch (const Error& e) {
    if (e.kind() != Error::Kind::simulator) throw;
    throw Error(std::string(e.what()) + " (on the one retry with " + change + "; the first run: " + first + ")",
                Error::Kind::simulator);
  }
}

}  // namespace gearpatch::spice
