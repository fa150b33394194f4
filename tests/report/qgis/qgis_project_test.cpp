// The QGIS project's XML through the one markup escaper (report/markup.hpp): names a run can
// carry (a report file name, exercise names from a column) read back whole from the .qgs by
// GDAL's XML parser, and a name the XML cannot hold (a control character, invalid UTF-8) no
// longer makes the project ill-formed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "report/qgis/qgis_project.hpp"
#include "xml_support.hpp"

namespace shoal::report {
namespace {

/// The first element named `name` below `n` (depth first), or null.
const CPLXMLNode* find(const CPLXMLNode* n, const std::string& name) {
    for (; n; n = n->psNext) {
        if (n->eType == CXT_Element && name == n->pszValue) return n;
        if (const CPLXMLNode* f = find(n->psChild, name)) return f;
    }
    return nullptr;
}

/// Every "name" attribute of the elements named `element` below `n`, in document order.
void names_of(const CPLXMLNode* n, const std::string& element, std::vector<std::string>& out) {
    for (; n; n = n->psNext) {
        if (n->eType == CXT_Element && element == n->pszValue) out.push_back(test::attr(n, "name"));
        if (n->eType == CXT_Element) names_of(n->psChild, element, out);
    }
}

TEST(QgisProject, NamesWithMarkupReadBackWholeAndTheForbiddenOnesLeaveItWellFormed) {
    ProjectView view;
    view.x0 = -1.5, view.y0 = 50.6, view.x1 = -1.1, view.y1 = 50.9;
    view.exercises = {"Ann's <run> & \"B\"", std::string("bell\x07") + "end", std::string("bad\xFF") + "byte"};
    const std::vector<ProjectLayer> layers = {{"events", "Point", "./r&d's.geojson"}, {"tracks", "Line", "./r&d's.tracks.geojson"}};
    const std::string qgs = qgis_project_xml(layers, "r&d's <report>", view);

    std::string error;
    const test::XmlPtr doc = test::parse_xml(qgs, &error);
    ASSERT_TRUE(doc) << "the project is not well-formed XML: " << error;

    const CPLXMLNode* title = find(doc.get(), "title");
    ASSERT_TRUE(title && title->psChild);
    EXPECT_EQ(std::string(title->psChild->pszValue), "shoal report r&d's <report>");

    std::vector<std::string> groups;
    names_of(doc.get(), "layer-tree-group", groups);
    // The root group has no name; then the exclusive group and one group per exercise.
    const std::vector<std::string> want = {"", "exercises", "exercise Ann's <run> & \"B\"", "exercise bell end",
                                           "exercise bad\xEF\xBF\xBD" "byte"};
    EXPECT_EQ(groups, want);

    // An exercise's subset keeps its quotes as QGIS writes them: `'` stays (attributes are all
    // in double quotes), `"` is &quot;.
    EXPECT_NE(qgs.find("|subset=&quot;exercise&quot; = 'Ann''s &lt;run&gt; &amp; &quot;B&quot;'"), std::string::npos);
    EXPECT_EQ(qgs.find("&apos;"), std::string::npos);
}

}  // namespace
}  // namespace shoal::report
