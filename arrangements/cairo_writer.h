// The drawing as PDF, EPS or PNG, through cairo (Debian's libcairo2-dev): the
// same regions, layers, chains and styles as the SVG (svg_writer.h), on the
// same page. PDF and EPS are in points at true size (a page in mm, or the pixel
// canvas at 96 px per inch); PNG at 96 px per inch.
#pragma once
#include <string>

#include "arrangements/sheet.h"
#include "arrangements/svg_writer.h"

namespace vismap {

// Whether this build has cairo (else the formats are refused).
bool cairo_available();

// format: "pdf", "eps" or "png". Throws std::runtime_error if cairo fails.
std::string to_cairo(const VisibilityMap& map, const Drawing& drawing, const Scene& scene, const View& view,
                     const SvgOptions& opt, const std::string& format);

// A drawing sheet (sheet.h) as PDF, EPS or PNG: the SVG sheet's page, views and labels.
std::string to_sheet_cairo(const std::vector<SheetView>& views, const Scene& scene, const SvgOptions& opt,
                           const std::string& note, const std::string& format);

}  // namespace vismap
