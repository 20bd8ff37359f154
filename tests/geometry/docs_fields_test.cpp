// The key tables of docs/*.md are the field lists' (scene_fields.hpp): each generated region,
// `<!-- fields: SECTION -->` ... `<!-- /fields -->`, must be what fields_table(SECTION) gives,
// and every section must have one. KIRI_UPDATE_DOCS=1 rewrites the regions instead of failing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "kiri/geometry/scene/scene_fields.hpp"

namespace fs = std::filesystem;
using namespace kiri::geometry;

namespace {

const fs::path docs = fs::path(KIRI_DATA_DIR) / ".." / "docs";
const std::string open_mark = "<!-- fields: ", close_mark = "<!-- /fields -->";

std::string read(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The text with each region's table replaced by the generated one; `seen` counts the sections.
std::string regenerated(const std::string& text, const fs::path& file, std::map<std::string, int>& seen)
{
    std::string out;
    std::size_t at = 0;
    for (std::size_t open; (open = text.find(open_mark, at)) != std::string::npos;) {
        const std::size_t name_end = text.find(" -->", open);
        const std::size_t body = text.find('\n', name_end) + 1;
        const std::size_t close = text.find(close_mark, body);
        EXPECT_NE(close, std::string::npos) << file << ": a fields region is not closed";
        if (close == std::string::npos)
            return text;
        const std::string section = text.substr(open + open_mark.size(), name_end - open - open_mark.size());
        ++seen[section];
        std::string table;
        try {
            table = fields_table(section);
        } catch (const std::exception& e) {
            ADD_FAILURE() << file << ": " << e.what();
            table = text.substr(body, close - body);
        }
        out += text.substr(at, body - at) + table;
        at = close;
    }
    return out + text.substr(at);
}

TEST(DocsFields, KeyTablesAreTheFieldLists)
{
    const bool update = std::getenv("KIRI_UPDATE_DOCS") && std::string(std::getenv("KIRI_UPDATE_DOCS")) == "1";
    std::map<std::string, int> seen;
    for (const auto& entry : fs::directory_iterator(docs)) {
        if (entry.path().extension() != ".md")
            continue;
        const std::string text = read(entry.path());
        const std::string expected = regenerated(text, entry.path(), seen);
        if (expected == text)
            continue;
        if (update) {
            std::ofstream(entry.path(), std::ios::binary) << expected;
            continue;
        }
        ADD_FAILURE() << entry.path() << ": a key table differs from its field list; "
                      << "rebuild and run this test with KIRI_UPDATE_DOCS=1 to regenerate it";
    }
    for (const std::string& section : documented_sections())
        EXPECT_EQ(seen[section], 1) << "docs/*.md should hold the key table of \"" << section << "\" once";
}

TEST(DocsFields, UnknownSectionsAreRefused) { EXPECT_THROW(fields_table("layer"), std::invalid_argument); }

}  // namespace
