#include "common/notices.h"

#include <utility>

namespace gearpatch {
namespace {

NoticeSink& sink() {
  static NoticeSink installed;
  return installed;
}

}  // namespace

void set_notice_sink(NoticeSink s) { sink() = std::move(s); }

void notice(std::string_view text) {
  if (sink()) sink()(text);
}

}  // namespace gearpatch
