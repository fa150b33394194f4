#pragma once
// Reading the XML shoal writes (SVG pictures, HTML debrief pages) in tests, with GDAL's own
// parser (cpl_minixml), so that a page that is not well-formed fails the test.

#include <cpl_error.h>
#include <cpl_minixml.h>

#include <functional>
#include <string>

#include "util/gdal_support.hpp"

namespace shoal::test {

using XmlPtr = CPLXMLTreeCloser;

/// The parsed document, or null (with GDAL's message in `error`) when it is not well-formed.
inline XmlPtr parse_xml(const std::string& text, std::string* error) {
    shoal::detail::QuietErrors quiet;
    XmlPtr doc(CPLParseXMLString(text.c_str()));
    if (!doc && error) *error = CPLGetLastErrorMsg();
    return doc;
}

/// The value of attribute `name` of element `n`; "" when it has none.
inline std::string attr(const CPLXMLNode* n, const char* name) {
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
        if (c->eType == CXT_Attribute && std::string(c->pszValue) == name && c->psChild) return c->psChild->pszValue;
    return {};
}

/// `n` (when an element) and every element under it, depth first.
inline void each_element(const CPLXMLNode* n, const std::function<void(const CPLXMLNode*)>& f) {
    if (n->eType != CXT_Element) return;
    f(n);
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext) each_element(c, f);
}

}  // namespace shoal::test
