// test_subdomain_size.cpp: Mesh/Subdomain Size, read from the example inputs
// as a user gives it: the accepted forms (Grid, 0, Auto, a whole number, an
// int in the XML file) and the refused ones; the grid of boxes a size gives
// the brick; the measured Auto rule (H = 4 while that gives at most 12000
// subdomains, 6 beyond, lowered until every rank has a subdomain; for a mesh
// file 6 up to 25 000 nodes per rank, the box's rule beyond);
// and the METIS count of a mesh file, (H+1)^3 nodes per subdomain, at least
// one per rank and per body and at most one per cell, unknown until the file
// is read.
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_UnitTestRepository.hpp>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "Tribos_Input.hpp"
#include "Tribos_InputXml.hpp"

using namespace Tribos;

namespace {

std::string sourceFile(const std::string& relative) {
  const char* dir = std::getenv("TRIBOS_SOURCE_DIR");
  return std::string(dir ? dir : ".") + "/" + relative;
}

RCP<Teuchos::ParameterList> brick(int level, const std::string& size) {
  return Input::read(sourceFile("input/brick_coulomb_F03.xml"),
                     {"Mesh/Level=" + std::to_string(level), "Mesh/Subdomain Size=" + size});
}

int count(const Mesh::DecompositionSpec& d) {
  return d.partitioner == "METIS" ? d.subdomains : d.grid[0] * d.grid[1] * d.grid[2];
}

}  // namespace

TEUCHOS_UNIT_TEST(SubdomainSize, AcceptedAndRefusedForms) {
  TEST_EQUALITY(Input::subdomainSizing(*brick(4, "Grid")).kind, Input::SubdomainSizing::Grid);
  TEST_EQUALITY(Input::subdomainSizing(*brick(4, "0")).kind, Input::SubdomainSizing::Grid);
  TEST_EQUALITY(Input::subdomainSizing(*brick(4, "Auto")).kind, Input::SubdomainSizing::Auto);
  const auto fixed = Input::subdomainSizing(*brick(4, "3"));
  TEST_EQUALITY(fixed.kind, Input::SubdomainSizing::Fixed);
  TEST_EQUALITY(fixed.H, 3);
  for (const char* bad : {"-1", "4x", "4.5", "auto", "", "1000001", "99999999999999999999"})
    TEST_THROW(brick(4, bad), std::exception);
  // An int in an XML file (the type before Auto existed) is its text.
  {
    std::ifstream in(sourceFile("input/brick_coulomb_F03.xml"));
    std::stringstream text;
    text << in.rdbuf();
    std::string xml = text.str();
    const std::string level = "<Parameter name=\"Level\" type=\"int\" value=\"4\"/>";
    const auto at = xml.find(level);
    TEST_ASSERT(at != std::string::npos);
    xml.insert(at + level.size(), "<Parameter name=\"Subdomain Size\" type=\"int\" value=\"2\"/>");
    const auto file = std::filesystem::temp_directory_path() / "tribos_test_subdomain_size_int.xml";
    std::ofstream(file) << xml;
    const auto fromInt = Input::subdomainSizing(*Input::read(file.string(), {}));
    std::filesystem::remove(file);
    TEST_EQUALITY(fromInt.kind, Input::SubdomainSizing::Fixed);
    TEST_EQUALITY(fromInt.H, 2);
  }
  // Without the parameter, the file's grid of 3 unit cubes.
  const auto seed = Input::read(sourceFile("input/brick_coulomb_F03.xml"), {"Mesh/Level=4"});
  const auto d = Input::decompositionSpec(*seed, 1);
  TEST_EQUALITY(count(d), 3);
  TEST_EQUALITY(d.size, 0);
}

TEUCHOS_UNIT_TEST(SubdomainSize, FixedSizeGivesTheGridOfBoxes) {
  // Level 8: 24 x 8 x 8 cells; boxes of 2 cells: 12 x 4 x 4.
  const auto d = Input::decompositionSpec(*brick(8, "2"), 1);
  TEST_EQUALITY(d.grid[0], 12);
  TEST_EQUALITY(d.grid[1], 4);
  TEST_EQUALITY(d.grid[2], 4);
  TEST_EQUALITY(d.size, 2);
}

TEUCHOS_UNIT_TEST(SubdomainSize, AutoRuleOnTheBrick) {
  struct Case {
    int level, ranks, H;
    std::array<int, 3> grid;
  };
  const std::vector<Case> cases = {
      {12, 1, 4, {9, 3, 3}},      // 36 x 12 x 12 cells: 81 subdomains of 4
      {24, 2, 4, {18, 6, 6}},     // 648 of 4
      {36, 2, 4, {27, 9, 9}},     // 2187 of 4
      {48, 2, 4, {36, 12, 12}},   // the million-dof brick: 5184 of 4
      {60, 2, 4, {45, 15, 15}},   // 10125 of 4, the largest count measured
      {64, 2, 6, {32, 8, 8}},     // 12288 of 4 would be too many: boxes of about 6 (8 cells across 64)
      {4, 1, 4, {3, 1, 1}},       // the seed's own three cubes
      {4, 4, 3, {4, 1, 1}},       // 3 boxes of 4 are fewer than 4 ranks: boxes of 3
      {1, 2, 1, {3, 1, 1}},       // 3 x 1 x 1 cells: one box per cell
  };
  for (const auto& c : cases) {
    const auto d = Input::decompositionSpec(*brick(c.level, "Auto"), c.ranks);
    out << "level " << c.level << ", " << c.ranks << " rank(s): H " << d.size << ", grid " << d.grid[0] << " x "
        << d.grid[1] << " x " << d.grid[2] << "\n";
    TEST_EQUALITY(d.size, c.H);
    for (int a = 0; a < 3; ++a) TEST_EQUALITY(d.grid[a], c.grid[a]);
  }
}

TEUCHOS_UNIT_TEST(SubdomainSize, MeshFileCountFromItsNodes) {
  auto params = [](const std::string& size) {
    return Input::read(sourceFile("input/gmsh_block_pressure.xml"), {"Mesh/Subdomain Size=" + size});
  };
  // Unknown before the file is read.
  TEST_EQUALITY(Input::decompositionSpec(*params("Auto"), 2).subdomains, 0);
  struct Case {
    const char* size;
    double nodes, cells;
    int ranks, H, subdomains, bodies = 1;
  };
  const std::vector<Case> cases = {
      {"Auto", 7683, 43064, 2, 6, 22},    // few nodes per rank: parts of 7^3 nodes
      {"Auto", 37326, 2e5, 2, 6, 109},    // 18 663 per rank: still 7^3
      {"Auto", 37326, 2e5, 1, 4, 299},    // 37 326 on one rank: the box's rule
      {"Auto", 60000, 3e5, 2, 4, 480},    // beyond 25 000 per rank: the box's rule
      {"Auto", 125000, 7e5, 2, 4, 1000},  // 1000 parts of 5^3 nodes
      {"Auto", 1.5e6, 8e6, 2, 4, 12000},  // 12000 parts of 4: still 4
      {"Auto", 2e6, 1e7, 2, 6, 5831},     // 16000 of 4 would be too many: 2e6 / 7^3
      {"Auto", 100, 400, 3, 2, 4},        // fewer parts of 4 and 3 than ranks: 100 / 3^3
      {"4", 100, 400, 3, 4, 3},           // a given size: one part per rank at least
      {"1", 1000, 5, 1, 1, 5},            // at most one part per cell
      {"20", 2000, 9000, 1, 20, 3, 3},    // 2000 / 21^3 rounds to 0: one part per body at least
  };
  for (const auto& c : cases) {
    const MeshSize size{c.nodes, c.cells, c.bodies};
    const auto d = Input::decompositionSpec(*params(c.size), c.ranks, &size);
    out << c.size << ", " << c.nodes << " nodes, " << c.ranks << " rank(s): H " << d.size << ", "
        << d.subdomains << " METIS parts\n";
    TEST_EQUALITY(d.partitioner, "METIS");
    TEST_EQUALITY(d.size, c.H);
    TEST_EQUALITY(d.subdomains, c.subdomains);
  }
}

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}

// Auto is the default; an input that gives its decomposition (Subdomain
// Grid, or Subdomains for METIS) and no size keeps it, and the list says so.
TEUCHOS_UNIT_TEST(SubdomainSize, DefaultIsAutoUnlessTheInputGivesItsDecomposition) {
  auto sizeOf = [](const std::string& input, const std::vector<std::string>& sets = {}) {
    return Input::read(sourceFile("input/" + input), sets)->sublist("Mesh").get<std::string>("Subdomain Size");
  };
  TEST_EQUALITY(sizeOf("prism_tresca.xml"), "Auto");  // names no decomposition
  TEST_EQUALITY(sizeOf("brick_coulomb_F03.xml"), "Grid");  // Subdomain Grid {3, 1, 1}
  TEST_EQUALITY(sizeOf("gmsh_block_pressure.xml"), "Grid");  // Subdomains 2
  TEST_EQUALITY(sizeOf("prism_tresca.xml", {"Mesh/Subdomain Grid={2,1,1}"}), "Grid");
  TEST_EQUALITY(sizeOf("prism_tresca.xml", {"Mesh/Subdomains=3"}), "Grid");
  TEST_EQUALITY(sizeOf("brick_coulomb_F03.xml", {"Mesh/Subdomain Size=Auto"}), "Auto");
  TEST_EQUALITY(sizeOf("brick_coulomb_F03.xml", {"Mesh/Subdomain Size=6"}), "6");
  // The resolved lists written out and read again (the parameters written
  // beside a result, every entry explicit) give the same decompositions.
  for (const char* input : {"prism_tresca.xml", "brick_coulomb_F03.xml"}) {
    const auto list = Input::read(sourceFile(std::string("input/") + input), {});
    const std::string echo = (std::filesystem::temp_directory_path() /
                              ("tribos_subdomain_size_echo_" + std::to_string(::getpid()) + ".xml")).string();
    std::ofstream(echo) << Input::toXml(*list);
    const auto again = Input::read(echo, {});
    std::filesystem::remove(echo);
    TEST_EQUALITY(again->sublist("Mesh").get<std::string>("Subdomain Size"),
                  list->sublist("Mesh").get<std::string>("Subdomain Size"));
    TEST_EQUALITY(count(Input::decompositionSpec(*again, 1, nullptr)), count(Input::decompositionSpec(*list, 1, nullptr)));
  }
  TEST_ASSERT(count(Input::decompositionSpec(*Input::read(sourceFile("input/prism_tresca.xml"), {}), 1, nullptr)) > 1);
}
