// The individual freeform readers behind ReadFreeformText (freeform_reader.h). Each reports
// problems through the scanner and returns the surfaces it could build.
#pragma once

#include <string>
#include <vector>

#include "quadrix/freeform/surface.h"
#include "quadrix/import/freeform/text_scanner.h"

namespace quadrix::import::detail {

std::vector<freeform::Surface> ReadNewell(TextScanner& scanner, const std::string& baseName);
std::vector<freeform::Surface> ReadBpt(TextScanner& scanner, const std::string& baseName);
std::vector<freeform::Surface> ReadGeomview(TextScanner& scanner, const std::string& baseName);
std::vector<freeform::Surface> ReadObj(TextScanner& scanner, const std::string& baseName);

// "teapot[3]": the name given to surface `index` of a file.
std::string SurfaceName(const std::string& baseName, std::size_t index);

}  // namespace quadrix::import::detail
