// check_map: format first; the geometric checks only when the map is readable.
#include "verify/checker.h"
#include "verify/checks.h"

namespace vismap_check {

Report check_map(const vismap::Scene& scene, const std::string& json_text, const Options& opt) {
  Report rep;
  Failures fail;
  try {
    MapDoc doc = read_map(json_text, scene, fail);
    if (doc.usable) {
      Screen sc = make_screen(scene, doc, opt.crease_deg, opt.smooth, fail);
      Context c{sc, doc, opt, fail, rep};
      check_topology(c);
      check_regions(c);
      check_area(c);
      check_segments(c);
      check_coverage(c);
      if (doc.has_hidden) check_hidden(c);
    } else {
      fail.add("format: the map is too broken for the geometric checks");
    }
  } catch (const std::exception& e) {
    fail.add(std::string("internal: ") + e.what());
  }
  rep.ok = fail.count() == 0;
  rep.failures = fail.messages();
  return rep;
}

}  // namespace vismap_check
