// wqmesh: the table docs/paper-map.md (the paper's procedures and rules, each
// with its file and function) is kept true: every row names a file of the
// tree that defines or declares its function, and every procedure and rule of
// the paper's section 4 has a row.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace {

struct Row {
  std::string paper, file, function;
};

/// The rows of the table: lines "| paper | `file` | `function` |".
std::vector<Row> table_rows(const std::string& text) {
  std::vector<Row> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| ", 0) != 0) continue;
    std::vector<std::string> cells;
    std::size_t at = 1;
    while (at < line.size()) {
      const std::size_t bar = line.find('|', at);
      if (bar == std::string::npos) break;
      std::string cell = line.substr(at, bar - at);
      const std::size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
      at = bar + 1;
    }
    if (cells.size() != 3 || cells[1].size() < 2 || cells[1].front() != '`') continue;
    auto unquote = [](const std::string& c) { return c.substr(1, c.size() - 2); };
    rows.push_back({cells[0], unquote(cells[1]), unquote(cells[2])});
  }
  return rows;
}

TEST(PaperMap, EveryRowNamesAFunctionOfItsFile) {
  const std::string root = WQMESH_SOURCE_DIR;
  const std::string text = wqmesh::testing::read_file(root + "/docs/paper-map.md");
  ASSERT_FALSE(text.empty()) << "docs/paper-map.md is missing";
  const std::vector<Row> rows = table_rows(text);
  ASSERT_GE(rows.size(), 20u);
  for (const Row& r : rows) {
    const std::string source = wqmesh::testing::read_file(root + "/" + r.file);
    ASSERT_FALSE(source.empty()) << r.file << " (row \"" << r.paper << "\") is missing or empty";
    // "Class::name" is defined as "Class::name(" in its .cpp; a free function
    // or a header's inline one as "name(".
    EXPECT_NE(source.find(r.function + "("), std::string::npos)
        << r.file << " does not define " << r.function << " (row \"" << r.paper << "\")";
  }
}

TEST(PaperMap, EveryProcedureAndRuleOfSection4HasARow) {
  const std::vector<Row> rows =
      table_rows(wqmesh::testing::read_file(std::string(WQMESH_SOURCE_DIR) + "/docs/paper-map.md"));
  const std::vector<std::string> names = {"WQMESH", "INITIALIZE", "CONFORM",          "REFINE", "PUMP",   "SPLITE",
                                          "SPLITF", "ENCROACH",   "protecting balls", "Rule 1", "Rule 2", "Rule 3",
                                          "Rule 4", "Rule 5",     "Rule 6",           "Rule 7"};
  for (const std::string& name : names) {
    bool found = false;
    for (const Row& r : rows) found = found || r.paper.rfind(name, 0) == 0;
    EXPECT_TRUE(found) << "no row of docs/paper-map.md starts with \"" << name << "\"";
  }
}

TEST(PaperMap, RulesAreNamedInTheRuleEnum) {
  // Each rule's enumerator starts with its number: rule1_..., ..., rule7_....
  const std::string rules = wqmesh::testing::read_file(std::string(WQMESH_SOURCE_DIR) + "/core/src/mesher/rules.h");
  ASSERT_FALSE(rules.empty());
  for (int n = 1; n <= 7; ++n) {
    const std::string enumerator = "rule" + std::to_string(n) + "_";
    EXPECT_NE(rules.find(enumerator), std::string::npos) << "no enumerator " << enumerator << "... in rules.h";
  }
}

TEST(PaperMap, PhasesGetTheirPiecesNotTheMesher) {
  // No god object (issue 13): each phase is handed the pieces it uses
  // (mesher.h lists them), so no phase file names class Mesher, and no class
  // of the mesher reaches into another's private members through `friend`.
  const std::string dir = std::string(WQMESH_SOURCE_DIR) + "/core/src/mesher/";
  for (const char* phase :
       {"initialize.cpp", "conform.cpp", "refine.cpp", "pump.cpp", "pump.h", "extract.cpp", "extract.h", "phases.h",
        "queues.cpp", "queues.h", "subcomplex.cpp", "subcomplex.h", "work_meter.cpp", "work_meter.h"}) {
    const std::string source = wqmesh::testing::read_file(dir + phase);
    ASSERT_FALSE(source.empty()) << dir << phase << " is missing or empty";
    EXPECT_EQ(source.find("Mesher::"), std::string::npos) << phase << " reaches into class Mesher";
    EXPECT_EQ(source.find("Mesher&"), std::string::npos) << phase << " is handed the whole Mesher";
    EXPECT_EQ(source.find("friend "), std::string::npos) << phase << " declares a friend";
  }
  for (const char* owner : {"mesher.h", "mesher.cpp", "rules.h", "domain.h", "protecting_balls.h"})
    EXPECT_EQ(wqmesh::testing::read_file(dir + owner).find("friend "), std::string::npos)
        << owner << " declares a friend";
}

}  // namespace
