#pragma once
/// The one markup escaper: text for the picture's SVG, the debrief's HTML and the QGIS
/// project's XML.

#include <string>
#include <string_view>

namespace shoal::report {

/// What becomes of `'`: the picture and the debrief escape it (`&apos;`: safe in any attribute
/// and in HTML); the QGIS project keeps it, its attributes being all in double quotes (an
/// exercise's subset `"exercise" = 'run'` reads as QGIS writes it).
enum class Apostrophe { escaped, kept };

/// Text for XML or HTML character data or an attribute value: `& < > "` escaped, `'` as
/// `apostrophe` says, invalid UTF-8 replaced by U+FFFD, the control characters XML 1.0 forbids
/// replaced by spaces.
std::string markup_text(std::string_view s, Apostrophe apostrophe = Apostrophe::escaped);

}  // namespace shoal::report
