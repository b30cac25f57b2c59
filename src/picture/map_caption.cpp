#include "rosmill/picture/map_caption.hpp"

#include <ctime>

namespace rosmill::core::picture {

std::string MapCaption::title() const {
  std::string t = map;
  if (!part.empty()) t += (t.empty() ? "" : " of ") + part;
  for (const std::string& s : {source, date.empty() ? local_iso_date() : date})
    if (!s.empty()) t += (t.empty() ? "" : ", ") + s;
  return t;
}

std::string local_iso_date() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &local);
  return buf;
}

}  // namespace rosmill::core::picture
