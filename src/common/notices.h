#pragma once
#include <functional>
#include <string_view>

namespace gearpatch {

/// Text the library has for the person at the terminal while it works: the
/// progress of a long run, a warning about an output it could not write. The
/// library hands it to a sink that main installs (only cli/ prints); without
/// a sink it is dropped, as in the tests.
using NoticeSink = std::function<void(std::string_view text)>;

/// Installs the sink (before any run starts: it is read without a lock).
void set_notice_sink(NoticeSink sink);

/// Hands `text` (whole lines, each ending in '\n') to the sink. Callers on
/// several threads serialise their calls.
void notice(std::string_view text);

}  // namespace gearpatch
