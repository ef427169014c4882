#include "Tribos_Input.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "Tribos_ComponentsValidator.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Validators.hpp"
#include "Tribos_Vec3.hpp"
#include "Tribos_FetiContact.hpp"
#include "Tribos_GmshReader.hpp"
#include "Tribos_MeshFile.hpp"
#include "Tribos_ParameterReader.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_SemismoothStarNewton.hpp"
#include "Tribos_ProjectedCG.hpp"

namespace Tribos {
namespace Input {

using Teuchos::Array;
using Teuchos::ParameterList;
using Teuchos::tuple;

namespace {

const char* const kSemismooth = "SemismoothStarNewton";

// The outer algorithms that solve the FETI dual, then the semismooth* method.
std::vector<std::string> outerAlgorithms() {
  auto names = Friction::dualSolverNames();
  names.push_back(kSemismooth);
  return names;
}

const Array<std::string> kFaces = tuple<std::string>("xmin", "xmax", "ymin", "ymax", "zmin", "zmax");

RCP<Teuchos::StringValidator> choice(const Array<std::string>& names) {
  return rcp(new Teuchos::StringValidator(names));
}

// Faces are the box's (xmin, ..., zmax) or, with Mesh/File, the physical
// surfaces of the file: no validator, validate() and checkMeshFaces() check
// the names against the mesh the run has.
const char* const kFaceDoc =
    "named boundary face: xmin, xmax, ymin, ymax, zmin, zmax of the box, or a physical surface name of Mesh/File";

const char* const kCurveDoc =
    "name of a curve of Load Curves: at the time t of a step the load is Value x curve(t); empty: Value x min(t, 1)";

ParameterList makeDirichletItem() {
  ParameterList p("Dirichlet item");
  p.set("Face", "xmin", kFaceDoc);
  p.set("Components", "xyz", "fixed components", componentsValidator());
  p.set("Value", Array<double>(3, 0.0), "prescribed displacement (x, y, z)");
  p.set("Curve", "", kCurveDoc);
  return p;
}

ParameterList makeTractionItem() {
  ParameterList p("Traction item");
  p.set("Face", "xmax", kFaceDoc);
  p.set("Value", Array<double>(3, 0.0), "surface traction (x, y, z), force per area");
  p.set("Curve", "", kCurveDoc);
  return p;
}

// Both entries are required (validateCurves): a default would give a curve
// of the other's length that its author never wrote.
ParameterList makeCurveItem() {
  ParameterList p("Load Curve item");
  p.set("Times", Array<double>(), "pseudo-times of the curve's points: at least 2, strictly increasing");
  p.set("Values", Array<double>(), "the curve's value at each of Times (linear between them, not extrapolated)");
  return p;
}

}  // namespace

const ParameterList& dirichletItem() {
  static const ParameterList p = makeDirichletItem();
  return p;
}
const ParameterList& tractionItem() {
  static const ParameterList p = makeTractionItem();
  return p;
}
const ParameterList& curveItem() {
  static const ParameterList p = makeCurveItem();
  return p;
}

ParameterList pairItem(const ParameterList& contact) {
  ParameterList p("pair");
  p.set("Slave Surface", "", "the face whose nodes are pressed on the master (the finer side)");
  p.set("Master Surface", "", "the face of the other body; empty: the rigid plane of Plane Point and Plane Normal");
  p.set("Type", "Contact", "Contact (unilateral, with friction) or Glued (bonded: no relative motion)",
        choice(tuple<std::string>("Contact", "Glued")));
  p.set("Plane Point", Array<double>(3, 0.0), "rigid plane: a point of it");
  p.set("Plane Normal", Array<double>(Teuchos::tuple<double>(0.0, 0.0, 1.0)),
        "rigid plane: its normal pointing out of the obstacle, towards the body (scaled to unit length)");
  p.set("Friction Law", contact.get<std::string>("Friction Law"), "Frictionless, Tresca or Coulomb",
        frictionLawValidator());
  p.set("Friction Coefficient", contact.get<double>("Friction Coefficient"), "Coulomb F", range<double>(0.0, 1e6));
  p.set("Slip Bound Traction", contact.get<double>("Slip Bound Traction"), "Tresca slip bound per area",
        range<double>(0.0, 1e300));
  p.set("Search Distance", 0.0,
        "slave nodes farther than this from their closest point on the master (or from the plane) take no part "
        "(a warning names them); 0: Auto, 5 % of the diagonal of the slave surface's bounding box and at least 4 "
        "times the largest prescribed displacement, the nodes it leaves out proved to stay out of contact after "
        "every step (a step where they might not is not converged); 1e300: every slave node (docs/contact.md)",
        range<double>(0.0, 1e300));
  p.set("Discretization", "Mortar",
        "Mortar (dual mortar segments: consistent nodal forces, passes the contact patch test; docs/contact.md) or "
        "Node To Segment (each slave node on its closest master facet)",
        Contact::discretizationValidator());
  return p;
}

ParameterList bodyItem(const ParameterList& material) {
  ParameterList p("body");
  p.sublist("Material").setParameters(material);
  // Beside the body's Material: what a body is at t = 0 is a property of
  // the body, named where its other properties are (and checked against
  // the mesh's bodies with them, checkMeshFaces).
  p.set("Initial Velocity", Array<double>(),
        "Dynamics: the velocity (x, y, z) at t = 0 of this body's nodes, Dirichlet dofs aside; empty (the "
        "default): Initial Conditions/Velocity. Bodies that share nodes (bonded) need the same velocity");
  return p;
}

RCP<const ParameterList> validParameters() {
  static RCP<ParameterList> pl;
  if (!pl.is_null()) return pl;
  pl = Teuchos::parameterList("Tribos");
  pl->set("Problem Name", "tribos", "name of the problem in the summary");
  ParameterList& mesh = pl->sublist("Mesh", false, "structured box mesh, or a mesh read from a Gmsh file");
  mesh.set("File", "",
           "mesh file: Gmsh (.msh version 4, ASCII or binary, or a .geo script meshed at run time when Run Geo "
           "Script allows it; physical volumes "
           "are bodies, physical surfaces are faces) or Exodus II (.exo, .e, .ex2, .g; element blocks are bodies, "
           "side sets are faces, node sets may carry Dirichlet conditions), relative to the input file's directory "
           "(also when given by --set) or absolute; empty: the box. With a file, Element, the ranges, Cells and Level "
           "are ignored, faces are named as in the file, and the decomposition is METIS per body (Partitioner = "
           "Structured is taken as METIS with the Subdomain Grid's number of subdomains, spread over the bodies by "
           "their cell counts)");
  mesh.set("Run Geo Script", false,
           "a .geo File is a Gmsh program: it can run shell commands (System) and read other files (Include), so it "
           "runs only when the input opts in here; it is then meshed by the gmsh program in a child process limited "
           "to Geo Time Limit and to the run's memory (--max-memory, or the machine's available memory)");
  mesh.set("Geo Time Limit", 600.0,
           "seconds Gmsh may take to mesh a .geo File (wall clock and CPU); it is stopped at the limit",
           range<double>(0.1, 86400.0));
  mesh.set("Element", "Tet4", "cell type of the box: Tet4 and Hex8 (first order), Tet10 and Hex20 (second order, "
           "no contact yet)", choice(tuple<std::string>("Tet4", "Hex8", "Tet10", "Hex20")));
  mesh.set("X Range", Array<double>(Teuchos::tuple<double>(0.0, 1.0)), "box extent along x");
  mesh.set("Y Range", Array<double>(Teuchos::tuple<double>(0.0, 1.0)), "box extent along y");
  mesh.set("Z Range", Array<double>(Teuchos::tuple<double>(0.0, 1.0)), "box extent along z");
  mesh.set("Cells", Array<int>(Teuchos::tuple<int>(4, 4, 4)), "cells along x, y, z (used when Level = 0)");
  mesh.set("Level", 0, "refinement level; 0 uses Cells", range<int>(0, 1000));
  mesh.set("Level Rule", "Cells Per Unit Length",
           "how Level sets the cells: k cells per unit length, or the semismooth* prism rule "
           "nx = ceil(2^((L+4)/2)), ny = nz = ceil(2^((L+2)/2))",
           choice(tuple<std::string>("Cells Per Unit Length", "Prism")));
  mesh.set("Partitioner", "Structured", "Structured (a grid of boxes) or METIS",
           choice(tuple<std::string>("Structured", "METIS")));
  mesh.set("Subdomain Grid", Array<int>(Teuchos::tuple<int>(1, 1, 1)), "boxes along x, y, z (Structured)");
  mesh.set("Subdomain Size", "Auto",
           "Auto (the default, unless the input gives Subdomain Grid or Subdomains and no Subdomain Size: then "
           "Grid); Grid (or 0): the Subdomain Grid (Subdomains for METIS) as given; H, a positive integer: subdomains of "
           "about H cells per edge (the box: along each axis the divisor of the cell count nearest to cells / H, "
           "Structured or METIS; a mesh file: METIS parts of about (H+1)^3 nodes, at least one per rank and per "
           "body); Auto: the box: H = 4 while that gives at most 12000 subdomains, else 6; a mesh file: 6 up to "
           "25000 nodes per rank, the box's rule beyond; lowered until every rank has a "
           "subdomain. "
           "Small subdomains make the dense blocks of the explicit dual operator cheap (their memory grows like "
           "the size, their setup per dof like its cube) and the coarse problem (6 per subdomain) large, large "
           "ones make the dual problem small: docs/scaling.md measures 4 as the fastest on the brick at every "
           "count measured, up to 10125 subdomains (Tet4 bricks to 2 million dofs on 2 ranks), and larger METIS "
           "parts as the fastest on mesh files of up to 18700 nodes per rank");
  mesh.set("Subdomains", 1, "number of subdomains (METIS)", range<int>(1, 1000000));
  ParameterList& mat = pl->sublist("Material", false, "isotropic linear elastic material");
  mat.set("Young's Modulus", 2.1e11, "E > 0");
  mat.set("Poisson's Ratio", 0.3, "0 <= nu < 0.5 (nu = 0.5, an incompressible material, locks displacement elements)");
  mat.set("Density", 0.0,
          "mass per unit volume rho, read by Dynamics only, which needs rho > 0 for every body (a body named in "
          "Bodies gives its own)");
  pl->sublist("Bodies", false,
              "one sublist per body with its own \"Material\" (Young's Modulus, Poisson's Ratio, Density) and "
              "\"Initial Velocity\" (Dynamics); a body named here must exist in the mesh (the box is the one body "
              "\"body\"); bodies not named take Material and Initial Conditions/Velocity");
  ParameterList& bc = pl->sublist("Boundary Conditions", false, "Dirichlet conditions and loads");
  bc.sublist("Dirichlet", false, "one sublist per condition: Face, Components, Value, Curve");
  bc.sublist("Traction", false, "one sublist per load: Face, Value, Curve");
  bc.set("Volume Force", Array<double>(3, 0.0), "volume force density (x, y, z)");
  bc.set("Volume Force Curve", "",
         "name of a curve of Load Curves: at the time t of a step the volume force is Volume Force x curve(t); "
         "empty: Volume Force x min(t, 1)");
  ParameterList& steps = pl->sublist("Load Steps", false,
                                     "the load history: the pseudo-times at which the problem is solved, in order");
  steps.set("Times", Array<double>(1, 1.0),
            "step times: finite, positive, strictly increasing; at t = 1 every load without a Curve has its full "
            "Value. The default, one step at t = 1, is the static problem");
  ParameterList& dynamics = pl->sublist(
      "Dynamics", false,
      "implicit time stepping of the bodies in contact (docs/dynamics.md): every step the contact problem of K + "
      "4 M / dt^2 through FETI; a load acts as Value x its Curve at the physical time t, a load without a Curve "
      "at its full Value from t = 0 (no Load Steps)");
  dynamics.set("Enabled", false, "step in time; false: the static problem or the quasi-static Load Steps");
  dynamics.set("Time Step", 0.0, "dt > 0, fixed");
  dynamics.set("End Time", 0.0, "the time of the last step, at least Time Step; round(End Time / Time Step) steps");
  dynamics.set("Scheme", Contact::timeSchemeName(Contact::TimeScheme::ContactStabilizedNewmark),
               "Contact-Stabilized Newmark (Deuflhard, Krause and Ertel: energy never gained at contact) or Newmark "
               "(the trapezoidal rule, contact on the step's end: chatters and gains energy at impact)",
               choice(tuple<std::string>(Contact::timeSchemeName(Contact::TimeScheme::ContactStabilizedNewmark),
                                         Contact::timeSchemeName(Contact::TimeScheme::Newmark))));
  pl->sublist("Initial Conditions", false, "the state at t = 0 of a Dynamics run, which starts undeformed")
      .set("Velocity", Array<double>(3, 0.0),
           "the velocity of every node (x, y, z), Dirichlet dofs aside; a body's own Bodies/NAME/Initial Velocity "
           "replaces it on that body's nodes");
  pl->sublist("Load Curves", false,
              "one sublist per piecewise-linear curve, named by the loads' Curve: Times (at least 2, strictly "
              "increasing) and Values of the same length; a curve a load uses must cover every step time");
  ParameterList& contact = pl->sublist("Contact", false,
                                       "contact pairs (Pairs), or one face against a rigid plane parallel to it "
                                       "(Face, Gap)");
  contact.set("Enabled", false, "solve a contact problem");
  contact.set("Face", "zmin",
              "without Pairs: the contact face (a box face, or a planar surface of Mesh/File); the rigid plane lies a "
              "distance Gap beyond it, parallel to it. Not used with Pairs, where a value other than this default is refused");
  contact.set("Gap", 0.0,
              "without Pairs: initial normal gap between the face and the plane. Not used with Pairs, where a value "
              "other than this default is refused");
  contact.set("Friction Law", "Coulomb", "Frictionless, Tresca (given slip bound) or Coulomb (the default of every pair)",
              frictionLawValidator());
  contact.set("Friction Coefficient", 0.3, "Coulomb friction coefficient F (the default of every pair)",
              range<double>(0.0, 1e6));
  contact.set("Slip Bound Traction", 0.0, "Tresca slip bound as a traction, force per area (the default of every pair)",
              range<double>(0.0, 1e300));
  contact.sublist("Pairs", false,
                  "one sublist per contact pair: Slave Surface, Master Surface (empty: a rigid plane through Plane "
                  "Point with the unit normal Plane Normal pointing out of the obstacle), Type (Contact or Glued), "
                  "friction (Friction Law, Friction Coefficient, Slip Bound Traction; default: Contact's), Search "
                  "Distance, Discretization (Mortar, the default, or Node To Segment; docs/contact.md)");
  ParameterList& solver = pl->sublist("Solver", false, "solution algorithm");
  solver.set("Type", "Auto",
             "Monolithic (assembled global solve), FETI, or Auto: Monolithic without contact, FETI with it "
             "(contact problems are FETI's)",
             choice(tuple<std::string>("Auto", "Monolithic", "FETI")));
  // The FETI solve's choices (the list the solve validates again), and the
  // semismooth* method, which the driver runs itself.
  Array<std::string> outer(
      *Contact::fetiSolveParameters()->getEntry("Outer Algorithm").validator()->validStringValues());
  outer.push_back(kSemismooth);
  solver.set("Outer Algorithm", Contact::kAutoOuterAlgorithm,
             "contact problems: Auto (Coulomb friction: in a load history where Dirichlet conditions hold every "
             "body Semismooth Newton, matrix-free, followed by Algorithm2 if it stops short, otherwise Algorithm2; "
             "Algorithm1 for Tresca friction and frictionless contact); " + Friction::dualSolverDocumentation() + "; " + kSemismooth +
                 " (Tresca or frictionless by the semismooth* Newton method). An alias is read as the algorithm it "
                 "names, and the effective parameters name that algorithm",
             choice(outer));
  // The result check's parameters, as the FETI solve defines them.
  for (const char* name : {"Result Check Factor", "Result Check Rounds"})
    solver.setEntry(name, Contact::fetiSolveParameters()->getEntry(name));
  Friction::FrictionSolverFactory::addValidParameters(solver);
  solver.sublist("SemismoothStarNewton").setParameters(*Semismooth::SemismoothStarNewton::getValidParameters());
  solver.sublist("Monolithic").setParameters(*Fem::MonolithicSystem::getValidParameters());
  ParameterList& feti = solver.sublist("FETI", false, "Total FETI: local solver, gluing, dual solver");
  feti.setParameters(*Feti::FetiProblem::getValidParameters());
  ParameterList& out = pl->sublist("Output", false, "result files");
  out.set("Directory", "output", "directory for the HDF5/XDMF files (overridden by --output)");
  out.set("Base Name", "solution", "file name without extension");
  out.set("Write Results", true, "write the HDF5/XDMF result files");
  out.set("Step Stride", 1,
          "a run of several steps (Load Steps, Dynamics) writes the data file and index entry of every k-th step "
          "and of the last (and of a step that fails); the steps table keeps a row per step, written with the next "
          "written step, and a restart continues from the last written step. At most " +
              std::to_string(kMaxStepStride) + ": the rows of the steps between two written ones are held in memory",
          range<int>(1, kMaxStepStride));
  return pl;
}

namespace {

std::string joinNames(const ParameterList& list) {
  std::string s;
  for (auto it = list.begin(); it != list.end(); ++it) s += (s.empty() ? "" : ", ") + list.name(it);
  return s;
}

void validateItems(ParameterList& collection, const ParameterList& item, const std::string& path) {
  for (auto it = collection.begin(); it != collection.end(); ++it) {
    const std::string name = collection.name(it);
    TRIBOS_REQUIRE(collection.isSublist(name), "parameter \"" << path << "/" << name
                                                              << "\" must be a sublist with keys: " << joinNames(item));
    ParameterList& sub = collection.sublist(name);
    TRIBOS_REQUIRE(sub.isParameter("Face"), "\"" << path << "/" << name << "\" has no \"Face\"; valid faces: xmin, xmax, ymin, ymax, zmin, zmax");
    for (auto jt = sub.begin(); jt != sub.end(); ++jt)
      TRIBOS_REQUIRE(item.isParameter(sub.name(jt)), "unknown parameter \"" << path << "/" << name << "/" << sub.name(jt)
                                                                           << "\"; valid: " << joinNames(item));
    sub.validateParametersAndSetDefaults(item, 0);
    const auto& v = sub.get<Array<double>>("Value");
    TRIBOS_REQUIRE(v.size() == 3, "\"" << path << "/" << name << "/Value\" needs 3 components, got " << v.size());
  }
}

// An int given where a double is expected is promoted (lossless), and where
// a string is expected written as text (a parameter that takes a number or
// a word, e.g. Mesh/Subdomain Size); any other mismatch names the parameter
// and both types.
void promoteType(ParameterList& user, const std::string& name, const Teuchos::any& wanted, const std::string& full) {
  const Teuchos::any& given = user.getEntry(name).getAny();
  if (given.type() == wanted.type()) return;
  if (given.type() == typeid(int) && wanted.type() == typeid(double)) {
    user.set(name, static_cast<double>(user.get<int>(name)));
    return;
  }
  if (given.type() == typeid(int) && wanted.type() == typeid(std::string)) {  // e.g. Mesh/Subdomain Size = 4
    user.set(name, std::to_string(user.get<int>(name)));
    return;
  }
  if (given.type() == typeid(Array<int>) && wanted.type() == typeid(Array<double>)) {
    const auto& a = user.get<Array<int>>(name);
    user.set(name, Array<double>(a.begin(), a.end()));
    return;
  }
  throw Error("parameter \"" + full + "\" has type " + IO::parameterTypeName(given) + " but must be of type " +
              IO::parameterTypeName(wanted));
}

// The validator's verdict said in one line naming the parameter, the value
// and what is allowed (Teuchos' own messages span several lines and name
// the list as "Tribos->Solver->FETI").
template <class T>
void checkRange(const Teuchos::ParameterEntry& entry, const Teuchos::ParameterEntryValidator* v, const std::string& full) {
  const auto* range = dynamic_cast<const Teuchos::EnhancedNumberValidator<T>*>(v);
  if (!range || entry.getAny().type() != typeid(T)) return;
  const T x = Teuchos::any_cast<T>(entry.getAny());
  TRIBOS_REQUIRE((!range->hasMin() || x >= range->getMin()) && (!range->hasMax() || x <= range->getMax()),
                 "parameter \"" << full << "\" = " << x << ": must lie in [" << range->getMin() << ", "
                                 << range->getMax() << "]");
}

void checkValidator(const Teuchos::ParameterEntry& entry, const Teuchos::ParameterEntry& valid, const std::string& full) {
  const auto validator = valid.validator();
  if (validator.is_null()) return;
  const auto choices = validator->validStringValues();
  if (!choices.is_null() && entry.getAny().type() == typeid(std::string)) {
    const std::string value = Teuchos::any_cast<std::string>(entry.getAny());
    std::string list;
    bool found = false;
    for (const auto& c : *choices) found = found || c == value, list += (list.empty() ? "" : ", ") + c;
    TRIBOS_REQUIRE(found, "parameter \"" << full << "\" = \"" << value << "\": valid values are " << list);
  }
  checkRange<int>(entry, validator.get(), full);
  checkRange<double>(entry, validator.get(), full);
}

void validateLevel(ParameterList& user, const ParameterList& valid, const std::string& path);

// Sublists of any name, each validated against `item` (defaults filled).
void validateNamedItems(ParameterList& collection, const ParameterList& item, const std::string& path) {
  for (auto it = collection.begin(); it != collection.end(); ++it) {
    const std::string name = collection.name(it);
    TRIBOS_REQUIRE(collection.isSublist(name), "parameter \"" << path << "/" << name
                                                              << "\" must be a sublist with keys: " << joinNames(item));
    validateLevel(collection.sublist(name), item, path + "/" + name);
  }
}

// Load Curves: each a sublist with both Times and Values (types checked as
// every value's); their lengths and order are the curve's (loadCurve()).
void validateCurves(ParameterList& curves, const std::string& path) {
  for (auto it = curves.begin(); it != curves.end(); ++it) {
    const std::string name = curves.name(it), full = path + "/" + name;
    TRIBOS_REQUIRE(curves.isSublist(name), "parameter \"" << full << "\" must be a sublist with keys: Times, Values");
    for (const char* key : {"Times", "Values"})
      TRIBOS_REQUIRE(curves.sublist(name).isParameter(key), "\"" << full << "\" has no \"" << key << "\"");
  }
  validateNamedItems(curves, curveItem(), path);
}

// Recursive validation with messages naming the full path of the parameter.
void validateLevel(ParameterList& user, const ParameterList& valid, const std::string& path) {
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string name = user.name(it);
    const std::string full = path.empty() ? name : path + "/" + name;
    TRIBOS_REQUIRE(valid.isParameter(name), "unknown parameter \"" << full << "\"; valid at this level: " << joinNames(valid));
    TRIBOS_REQUIRE(user.isSublist(name) == valid.isSublist(name),
                   "parameter \"" << full << "\" must be " << (valid.isSublist(name) ? "a sublist" : "a value, not a sublist"));
    if (!valid.isSublist(name)) {
      promoteType(user, name, valid.getEntry(name).getAny(), full);
      checkValidator(user.getEntry(name), valid.getEntry(name), full);
    }
  }
  user.validateParametersAndSetDefaults(valid, 0);
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string name = valid.name(it);
    if (!valid.isSublist(name)) continue;
    const std::string full = path.empty() ? name : path + "/" + name;
    if (full == "Boundary Conditions/Dirichlet") {
      validateItems(user.sublist(name), dirichletItem(), full);
    } else if (full == "Boundary Conditions/Traction") {
      validateItems(user.sublist(name), tractionItem(), full);
    } else if (full == "Load Curves") {
      validateCurves(user.sublist(name), full);
    } else if (full == "Contact/Pairs") {
      validateNamedItems(user.sublist(name), pairItem(user), full);
    } else if (full == "Bodies") {
      validateNamedItems(user.sublist(name), bodyItem(user.sublist("Material")), full);
    } else {
      validateLevel(user.sublist(name), valid.sublist(name), full);
    }
  }
}

// Teuchos' messages start with a throw location; keep the sentences that
// name the parameter, the value and the valid choices, on one line.
std::string cleanTeuchosMessage(const std::string& what) {
  std::string msg = what;
  auto pos = msg.find("\nThe \"");
  if (pos == std::string::npos) pos = msg.find("Error,");
  if (pos != std::string::npos) msg = msg.substr(pos);
  std::string out;
  bool blank = false;
  for (char c : msg) {
    if (c == '\n') {
      blank = true;
      continue;
    }
    if (blank && !out.empty()) out += "; ";
    blank = false;
    out += c;
  }
  const auto anon = out.find("ANONYMOUS->");
  if (anon != std::string::npos) out.erase(anon, 11);
  return out;
}

// Lists built in memory (embedding applications) bypass the strict reader:
// NaN and infinity are refused here as well.
void requireFinite(const ParameterList& list, const std::string& path) {
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string& name = list.name(it);
    const std::string full = path.empty() ? name : path + "/" + name;
    if (list.isSublist(name)) {
      requireFinite(list.sublist(name), full);
    } else if (list.isType<double>(name)) {
      TRIBOS_REQUIRE(std::isfinite(list.get<double>(name)), "parameter \"" << full << "\" is not a finite number");
    } else if (list.isType<Array<double>>(name)) {
      for (double v : list.get<Array<double>>(name))
        TRIBOS_REQUIRE(std::isfinite(v), "parameter \"" << full << "\" has a component that is not a finite number");
    }
  }
}

// The faces named by conditions and the contact, with the path of their parameter.
std::vector<std::pair<std::string, std::string>> namedFaces(const ParameterList& params) {
  std::vector<std::pair<std::string, std::string>> faces;
  const auto& bc = params.sublist("Boundary Conditions");
  for (const char* kind : {"Dirichlet", "Traction"}) {
    const auto& list = bc.sublist(kind);
    for (auto it = list.begin(); it != list.end(); ++it)
      faces.emplace_back("Boundary Conditions/" + std::string(kind) + "/" + list.name(it) + "/Face",
                         list.sublist(list.name(it)).get<std::string>("Face"));
  }
  const auto& contact = params.sublist("Contact");
  const auto& pairs = contact.sublist("Pairs");
  if (contact.get<bool>("Enabled") && pairs.numParams() == 0)
    faces.emplace_back("Contact/Face", contact.get<std::string>("Face"));
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const auto& pair = pairs.sublist(pairs.name(it));
    const std::string path = "Contact/Pairs/" + pairs.name(it);
    faces.emplace_back(path + "/Slave Surface", pair.get<std::string>("Slave Surface"));
    if (!pair.get<std::string>("Master Surface").empty())
      faces.emplace_back(path + "/Master Surface", pair.get<std::string>("Master Surface"));
  }
  return faces;
}

// A box has the faces xmin..zmax; other names need a mesh file (checked
// against the file's physical surfaces when it is read: checkMeshFaces).
void validateFaceNames(const ParameterList& params) {
  const bool file = !meshFile(params).empty();
  for (const auto& [path, face] : namedFaces(params)) {
    TRIBOS_REQUIRE(!face.empty(), "parameter \"" << path << "\" is empty; name a boundary face");
    if (file) continue;
    std::string valid;
    bool found = false;
    for (const auto& f : kFaces) found = found || f == face, valid += (valid.empty() ? "" : ", ") + f;
    TRIBOS_REQUIRE(found, "parameter \"" << path << "\" = \"" << face << "\": valid values are " << valid
                                         << " (the faces of the box); \"" << face
                                         << "\" may name a physical surface of a mesh read from Mesh/File");
  }
}

void validateMaterial(const ParameterList& m) {
  const double E = m.get<double>("Young's Modulus"), nu = m.get<double>("Poisson's Ratio");
  TRIBOS_REQUIRE(E > 0, "\"Material/Young's Modulus\" = " << E << ": must be positive");
  TRIBOS_REQUIRE(nu >= 0 && nu < 0.5, "\"Material/Poisson's Ratio\" = "
                                          << nu << ": must satisfy 0 <= nu < 0.5"
                                          << (nu == 0.5 ? " (nu = 0.5 is an incompressible material, which "
                                                          "displacement-based elements cannot represent)"
                                                        : ""));
}

// The longest Base Name: the longest file of the set (BASE.parameters.xml)
// and its temporary (.BASE.parameters.xml.<pid>.tmp) stay within the 255
// bytes a file name may have on every common file system.
constexpr size_t kMaxBaseName = 200;
// The longest Problem Name: a title, written as an HDF5 attribute (whose
// object header holds 64 KiB in all) and into the summary.
constexpr size_t kMaxProblemName = 1000;

// The first control character (C0 or DEL) of `text`, or npos.
size_t firstControl(const std::string& text) {
  for (size_t i = 0; i < text.size(); ++i)
    if (static_cast<unsigned char>(text[i]) < 0x20 || text[i] == 0x7f) return i;
  return std::string::npos;
}

void validateOutput(const ParameterList& out) {
  const std::string base = out.get<std::string>("Base Name");
  // Checked first: the messages below quote the name.
  const size_t control = firstControl(base);
  TRIBOS_REQUIRE(control == std::string::npos, "\"Output/Base Name\" holds the control character 0x"
                                                   << std::hex << static_cast<int>(static_cast<unsigned char>(base[control]))
                                                   << std::dec << " at byte " << control
                                                   << "; a file name of the result set takes printable characters");
  const std::string what = "\"Output/Base Name\" = \"" + base + "\": ";
  TRIBOS_REQUIRE(!base.empty() && base != "." && base != ".." && base.find('/') == std::string::npos,
                 what << "must be a file name without a directory (no '/'); "
                      << "use Output/Directory or --output for the directory");
  // The .xmf names its arrays FILE.h5:/path; a ':' in FILE would cut that reference.
  TRIBOS_REQUIRE(base.find(':') == std::string::npos,
                 what << "holds ':', which the .xmf index uses between the HDF5 file and its arrays");
  TRIBOS_REQUIRE(base.size() <= kMaxBaseName, "\"Output/Base Name\" has " << base.size() << " bytes; at most "
                                                                         << kMaxBaseName << " (file names end at 255)");
  TRIBOS_REQUIRE(!out.get<std::string>("Directory").empty(), "\"Output/Directory\" is empty");
}

void validateProblemName(const std::string& name) {
  TRIBOS_REQUIRE(name.size() <= kMaxProblemName, "\"Problem Name\" has " << name.size() << " bytes; at most "
                                                                        << kMaxProblemName << " (it is a title)");
}

// The outer algorithm checks its own parameters (e.g. Algorithm 2's Residual
// Balancing) when it is made; made here, before any work, its message gets
// the path of its list in the input file.
void checkOuterAlgorithm(const std::string& outer, const ParameterList& solver) {
  try {
    Friction::FrictionSolverFactory().create(outer, solver);
  } catch (const Error& e) {
    throw Error("Solver/" + std::string(e.what()));
  }
}

void checkSemismooth(const ParameterList& list) {
  try {
    Semismooth::SemismoothStarNewton::checkParameters(list);
  } catch (const Error& e) {
    throw Error(std::string("Solver/") + kSemismooth + ": " + e.what());
  }
}

// Why a contact pair does not read `entry` ("" when it does): a rigid plane
// (no Master Surface) reads Plane Point and Plane Normal, and a master
// surface the Discretization (against a plane both give the same rows); a
// contact pair reads its Friction Law and that law's own parameter
// (Coulomb: Friction Coefficient, Tresca: Slip Bound Traction); a glued pair
// has no friction.
std::string unusedPairEntry(const ParameterList& pair, const std::string& entry) {
  const bool plane = pair.get<std::string>("Master Surface").empty();
  const std::string law = pair.get<std::string>("Friction Law");
  if ((entry == "Plane Point" || entry == "Plane Normal") && !plane)
    return "a pair with a Master Surface contacts that surface, not a rigid plane";
  if (entry == "Discretization" && plane)
    return "against a rigid plane (no Master Surface) Mortar and Node To Segment give the same rows";
  if ((entry == "Friction Law" || entry == "Friction Coefficient" || entry == "Slip Bound Traction") &&
      pair.get<std::string>("Type") == "Glued")
    return "a pair of Type = Glued has no friction (its surfaces do not move relative to each other)";
  if (entry == "Friction Coefficient" && law != "Coulomb")
    return "Friction Law = " + law + " has no friction coefficient (Coulomb's)";
  if (entry == "Slip Bound Traction" && law != "Tresca")
    return "Friction Law = " + law + " has no given slip bound (Tresca's)";
  return "";
}

// Every entry of a pair that its kind does not read keeps its default (the
// effective parameters a run writes carry every default); another value is
// refused by name instead of ignored.
void requireEveryPairEntryUsed(const ParameterList& contact, const ParameterList& pair, const std::string& path) {
  const ParameterList defaults = pairItem(contact);
  for (auto it = pair.begin(); it != pair.end(); ++it) {
    const std::string& entry = pair.name(it);
    const std::string why = unusedPairEntry(pair, entry);
    if (why.empty() || pair.getEntry(entry).getAny(false) == defaults.getEntry(entry).getAny(false)) continue;
    std::ostringstream value;  // as the input writes it: "text", {0, 0, 1}, 0.5
    if (pair.isType<std::string>(entry)) {
      value << "\"" << pair.get<std::string>(entry) << "\"";
    } else if (pair.isType<Array<double>>(entry)) {
      const auto& a = pair.get<Array<double>>(entry);
      value << "{";
      for (size_t i = 0; i < a.size(); ++i) value << (i ? ", " : "") << a[i];
      value << "}";
    } else if (pair.isType<double>(entry)) {
      value << pair.get<double>(entry);
    } else {
      pair.getEntry(entry).getAny(false).print(value);
    }
    throw Error("\"" + path + "/" + entry + "\" = " + value.str() + " is not used: " + why + "; remove it");
  }
}

// Pairs: a slave surface, a usable plane normal, no entry their kind does
// not read, and Contact enabled.
void validatePairs(const ParameterList& params) {
  const auto& contact = params.sublist("Contact");
  const auto& pairs = contact.sublist("Pairs");
  TRIBOS_REQUIRE(pairs.numParams() == 0 || contact.get<bool>("Enabled"),
                 "Contact/Pairs names " << pairs.numParams() << " pair(s) but Contact/Enabled = false");
  // Face and Gap describe the one contact of a face against a rigid plane;
  // beside pairs they are not read. Their defaults stay accepted (the
  // effective parameters that a run writes carry every default).
  if (pairs.numParams() > 0) {
    const auto& defaults = validParameters()->sublist("Contact");
    TRIBOS_REQUIRE(contact.get<std::string>("Face") == defaults.get<std::string>("Face"),
                   "\"Contact/Face\" = \"" << contact.get<std::string>("Face")
                                          << "\" is not used with Contact/Pairs (each pair names its Slave Surface "
                                             "and Master Surface, or its rigid plane): remove it");
    TRIBOS_REQUIRE(contact.get<double>("Gap") == defaults.get<double>("Gap"),
                   "\"Contact/Gap\" = " << contact.get<double>("Gap")
                                      << " is not used with Contact/Pairs (a pair's gap is where its surfaces lie in "
                                         "the mesh, or where its Plane Point puts the rigid plane): remove it");
  }
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const std::string path = "Contact/Pairs/" + pairs.name(it);
    const auto& pair = pairs.sublist(pairs.name(it));
    TRIBOS_REQUIRE(!pair.get<std::string>("Slave Surface").empty(), "\"" << path << "/Slave Surface\" is empty");
    const auto& n = pair.get<Array<double>>("Plane Normal");
    const auto& x = pair.get<Array<double>>("Plane Point");
    TRIBOS_REQUIRE(n.size() == 3 && x.size() == 3, "\"" << path << "/Plane Normal\" and \"Plane Point\" need 3 components");
    TRIBOS_REQUIRE(norm(Vec3{n[0], n[1], n[2]}) > 0, "\"" << path << "/Plane Normal\" is zero");
    requireEveryPairEntryUsed(contact, pair, path);
  }
  // One friction law per run (Contact::runLaw): a Tresca pair beside a
  // Coulomb pair is refused naming the Friction Law of one of each.
  std::string tresca, coulomb;  // the path of the first such pair
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const auto& pair = pairs.sublist(pairs.name(it));
    if (pair.get<std::string>("Type") == "Glued") continue;
    const std::string law = pair.get<std::string>("Friction Law"), path = "Contact/Pairs/" + pairs.name(it);
    if (law == "Tresca" && tresca.empty()) tresca = path;
    if (law == "Coulomb" && coulomb.empty()) coulomb = path;
  }
  TRIBOS_REQUIRE(tresca.empty() || coulomb.empty(),
                 "contact pairs with Tresca and with Coulomb friction in one run (\""
                     << tresca << "/Friction Law\" = \"Tresca\", \"" << coulomb
                     << "/Friction Law\" = \"Coulomb\"): no outer algorithm solves both; make them all Coulomb (or "
                        "Tresca)");
  const auto& bodies = params.sublist("Bodies");
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    try {
      validateMaterial(bodies.sublist(bodies.name(it)).sublist("Material"));
    } catch (const Error& e) {
      std::string what = e.what();
      const auto at = what.find("\"Material/");
      if (at != std::string::npos) what.insert(at + 1, "Bodies/" + bodies.name(it) + "/");
      throw Error(what);
    }
  }
}

// The Curve parameters of the loads, with their paths: every Dirichlet
// condition, every traction, the volume force.
std::vector<std::pair<std::string, std::string>> curveReferences(const ParameterList& params) {
  std::vector<std::pair<std::string, std::string>> refs;
  const auto& bc = params.sublist("Boundary Conditions");
  for (const char* kind : {"Dirichlet", "Traction"}) {
    const auto& list = bc.sublist(kind);
    for (auto it = list.begin(); it != list.end(); ++it)
      refs.emplace_back("Boundary Conditions/" + std::string(kind) + "/" + list.name(it) + "/Curve",
                        list.sublist(list.name(it)).get<std::string>("Curve"));
  }
  refs.emplace_back("Boundary Conditions/Volume Force Curve", bc.get<std::string>("Volume Force Curve"));
  return refs;
}

void validateStepTimes(const std::vector<double>& times) {
  TRIBOS_REQUIRE(!times.empty(), "\"Load Steps/Times\" is empty; give at least one step time (without Load Steps "
                                 "the run is one step at t = 1)");
  for (size_t i = 0; i < times.size(); ++i) {
    TRIBOS_REQUIRE(std::isfinite(times[i]), "\"Load Steps/Times\": Times[" << i << "] = " << times[i] << " is not finite");
    TRIBOS_REQUIRE(times[i] > 0, "\"Load Steps/Times\": Times[" << i << "] = " << times[i]
                                                             << " is not positive; step times are positive (at t = 1 "
                                                                "the loads without a Curve have their full Value)");
    TRIBOS_REQUIRE(i == 0 || times[i] > times[i - 1], "\"Load Steps/Times\" must be strictly increasing; Times["
                                                          << i << "] = " << times[i] << " follows Times[" << i - 1
                                                          << "] = " << times[i - 1]);
  }
}

// Step times, every curve (its own checks), and every Curve a load names:
// defined, and covering every step time (a curve is not extrapolated).
void validateLoadHistory(const ParameterList& params) {
  const auto times = loadStepTimes(params);
  validateStepTimes(times);
  const auto& curves = params.sublist("Load Curves");
  for (auto it = curves.begin(); it != curves.end(); ++it) loadCurve(params, curves.name(it));
  for (const auto& [path, name] : curveReferences(params)) {
    if (name.empty()) continue;
    TRIBOS_REQUIRE(curves.isSublist(name), "parameter \"" << path << "\" = \"" << name
                                                           << "\": Load Curves defines no curve of that name; "
                                                           << (curves.numParams() ? "its curves are: " + joinNames(curves)
                                                                                  : std::string("it defines none")));
    const Fem::LoadCurve curve = loadCurve(params, name);
    for (double t : times)
      TRIBOS_REQUIRE(curve.covers(t), "parameter \"" << path << "\" = \"" << name << "\": \"Load Curves/" << name
                                                      << "\" is defined on [" << curve.times().front() << ", "
                                                      << curve.times().back() << "] and does not cover the step time "
                                                      << t << " of Load Steps/Times; a load curve is not extrapolated");
  }
}

// The most steps a Dynamics run may take: their times are held in memory
// and their files counted against the disk (requireDiskSpace) before any
// work.
constexpr double kMaxDynamicSteps = 1e7;

// Dynamics: a positive step, an end at least one step away and not too many
// steps, a positive density for every body, no Load Steps, curves that
// cover t = 0 and Dirichlet values 0 there (the run starts undeformed), and
// TFETI's positive definite subdomains (FETI, TFETI, not the semismooth*
// method). Before the load history, whose step times it makes.
void validateDynamics(const ParameterList& params) {
  if (!dynamics(params)) return;
  const auto& d = params.sublist("Dynamics");
  const double dt = d.get<double>("Time Step"), end = d.get<double>("End Time");
  TRIBOS_REQUIRE(dt > 0, "\"Dynamics/Time Step\" = " << dt << ": a Dynamics run needs a positive time step");
  TRIBOS_REQUIRE(end >= dt, "\"Dynamics/End Time\" = " << end << " is less than one Time Step (" << dt << ")");
  TRIBOS_REQUIRE(end / dt <= kMaxDynamicSteps, "\"Dynamics/End Time\" / \"Time Step\" = " << end / dt
                                                 << " steps; at most " << kMaxDynamicSteps << " are taken");
  const auto& v = params.sublist("Initial Conditions").get<Array<double>>("Velocity");
  TRIBOS_REQUIRE(v.size() == 3, "\"Initial Conditions/Velocity\" needs 3 components, has " << v.size());
  const auto& named = params.sublist("Bodies");
  for (auto it = named.begin(); it != named.end(); ++it) {
    const auto& own = named.sublist(named.name(it)).get<Array<double>>("Initial Velocity");
    TRIBOS_REQUIRE(own.empty() || own.size() == 3,
                   "\"Bodies/" << named.name(it) << "/Initial Velocity\" needs 3 components (or none: the body takes "
                                   "Initial Conditions/Velocity), has " << own.size());
  }
  // Without named bodies Material's density is every body's; with them, a
  // body the input does not name takes it, which the mesh tells
  // (requireEveryBodyDensity).
  TRIBOS_REQUIRE(params.sublist("Bodies").numParams() > 0 || params.sublist("Material").get<double>("Density") > 0,
                 "\"Material/Density\" = " << params.sublist("Material").get<double>("Density")
                                            << ": Dynamics needs the density of the bodies, rho > 0");
  const auto& bodies = params.sublist("Bodies");
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    const double rho = bodies.sublist(bodies.name(it)).sublist("Material").get<double>("Density");
    TRIBOS_REQUIRE(rho > 0, "\"Bodies/" << bodies.name(it) << "/Material/Density\" = " << rho
                                         << ": Dynamics needs the density of every body, rho > 0");
  }
  const bool loadSteps = params.isSublist("Load Steps") &&
                         params.sublist("Load Steps").get<Array<double>>("Times") != Array<double>(1, 1.0);
  TRIBOS_REQUIRE(!loadSteps, "\"Load Steps/Times\" is given with Dynamics/Enabled = true: a Dynamics run steps in "
                             "time by Dynamics/Time Step; remove Load Steps");
  // The run starts undeformed: every Dirichlet value is 0 at t = 0 (a
  // Value of 0, or a Curve that starts at 0); a load's Curve covers t = 0.
  for (const auto& [path, name] : curveReferences(params))
    TRIBOS_REQUIRE(name.empty() || !params.sublist("Load Curves").isSublist(name) || loadCurve(params, name).covers(0.0),
                   "parameter \"" << path << "\" = \"" << name << "\": a Dynamics run starts at t = 0, which \"Load "
                                  "Curves/" << name << "\" does not cover");
  const auto& dirichlet = params.sublist("Boundary Conditions").sublist("Dirichlet");
  for (auto it = dirichlet.begin(); it != dirichlet.end(); ++it) {
    const auto& item = dirichlet.sublist(dirichlet.name(it));
    const auto& value = item.get<Array<double>>("Value");
    const std::string curve = item.get<std::string>("Curve");
    const double atZero = curve.empty() || !params.sublist("Load Curves").isSublist(curve)
                              ? 1.0
                              : loadCurve(params, curve)(0.0);
    for (double v : value)
      TRIBOS_REQUIRE(v * atZero == 0, "\"Boundary Conditions/Dirichlet/" << dirichlet.name(it) << "\": its value at t = 0 "
                                     "is not 0, but a Dynamics run starts undeformed; give it a Curve that is 0 at "
                                     "t = 0 (a load without a Curve acts at its full Value from t = 0)");
  }
  const auto& solver = params.sublist("Solver");
  TRIBOS_REQUIRE(solver.get<std::string>("Type") != "Monolithic",
                 "Solver/Type = Monolithic: Dynamics steps through FETI (Type = FETI or Auto)");
  TRIBOS_REQUIRE(solver.get<std::string>("Outer Algorithm") != kSemismooth,
                 "Solver/Outer Algorithm = " << kSemismooth << " solves one static step; Dynamics steps through FETI");
  TRIBOS_REQUIRE(solver.sublist("FETI").get<std::string>("Formulation") != "FETI-1",
                 "Solver/FETI/Formulation = FETI-1: Dynamics solves TFETI's positive definite subdomains K + 4 M / "
                 "dt^2 (Dirichlet conditions as rows of B)");
}

// What the solvers cannot do over several steps, refused before any work.
void validateStepSolvers(const ParameterList& params) {
  const size_t steps = loadStepTimes(params).size();
  if (steps <= 1) return;
  const Method m = method(params);
  TRIBOS_REQUIRE(m != Method::Semismooth,
                 "\"Load Steps/Times\" has " << steps << " steps, but Solver/Outer Algorithm = " << kSemismooth
                                              << " solves one static step: its Tresca history (the slip bound acting on "
                                                 "the slip increment of each step) is not implemented; use Algorithm1 "
                                                 "or MSA+Algorithm1, or one step");
  const bool feti = m == Method::FetiLinear || m == Method::FetiContact;
  TRIBOS_REQUIRE(!feti || params.sublist("Solver").sublist("FETI").get<std::string>("Formulation") != "FETI-1",
                 "\"Load Steps/Times\" has "
                     << steps << " steps, but Solver/FETI/Formulation = FETI-1 eliminates the Dirichlet values "
                                 "from the subdomain matrices once, so they cannot follow their curves from step to "
                                 "step; use Formulation = TFETI (Dirichlet conditions as rows of B), or one step");
}

// An alias of an outer algorithm (Tresca for Algorithm1) is replaced by the
// algorithm's name where the input is read: every list built from the input
// (the FETI solve's, the effective parameters written beside the result)
// then holds the name that the solver's own choices hold.
void resolveOuterAlgorithm(ParameterList& solver) {
  const std::string outer = solver.get<std::string>("Outer Algorithm");
  if (outer == Contact::kAutoOuterAlgorithm || outer == kSemismooth) return;
  solver.set("Outer Algorithm", Friction::frictionSolvers().canonical(outer));
}

// Subdomain Size is Auto by default, the size measured fastest; an input
// that gives its decomposition (Subdomain Grid, or Subdomains for METIS) and
// no size keeps that decomposition. The list is resolved in place, so the
// parameters written beside the result say which was used.
void resolveSubdomainSize(ParameterList& mesh) {
  if (!mesh.getEntry("Subdomain Size").isDefault()) return;
  if (!mesh.getEntry("Subdomain Grid").isDefault() || !mesh.getEntry("Subdomains").isDefault())
    mesh.set("Subdomain Size", "Grid");
}

}  // namespace

void validate(ParameterList& params, const std::string& source) {
  try {
    validateLevel(params, *validParameters(), "");
    resolveSubdomainSize(params.sublist("Mesh"));
    resolveOuterAlgorithm(params.sublist("Solver"));
    const auto& mesh = params.sublist("Mesh");
    for (const char* key : {"X Range", "Y Range", "Z Range"}) {
      const auto& r = mesh.get<Array<double>>(key);
      TRIBOS_REQUIRE(r.size() == 2 && r[1] > r[0], "\"Mesh/" << key << "\" must be {lo, hi} with lo < hi");
    }
    subdomainSizing(params);  // a complete value
    for (const char* key : {"Cells", "Subdomain Grid"}) {
      const auto& c = mesh.get<Array<int>>(key);
      TRIBOS_REQUIRE(c.size() == 3 && c[0] > 0 && c[1] > 0 && c[2] > 0, "\"Mesh/" << key << "\" must be 3 positive integers");
    }
    const auto& contact = params.sublist("Contact");
    const auto& solver = params.sublist("Solver");
    validatePairs(params);
    // Glued pairs only: no unilateral contact, projected CG solves the run.
    bool unilateral = contact.sublist("Pairs").numParams() == 0;
    const auto& pairList = contact.sublist("Pairs");
    for (auto it = pairList.begin(); it != pairList.end(); ++it)
      unilateral = unilateral || pairList.sublist(pairList.name(it)).get<std::string>("Type") == "Contact";
    if (contact.get<bool>("Enabled") && unilateral) {
      const FrictionLaw law = Contact::runLaw(pairFriction(params));
      const std::string outer = method(params) == Method::Semismooth
                                    ? std::string(kSemismooth)
                                    : Contact::outerAlgorithmFor(solver.get<std::string>("Outer Algorithm"), pairFriction(params));
      TRIBOS_REQUIRE(outer != kSemismooth || contact.sublist("Pairs").numParams() == 0,
                     "Solver/Outer Algorithm = " << kSemismooth << " solves one face against a rigid plane (Contact/Face, "
                                                 "Gap); Contact/Pairs needs a FETI outer algorithm");
      TRIBOS_REQUIRE(solver.get<std::string>("Type") != "Monolithic" || outer == kSemismooth,
                     "contact problems are solved by FETI (Solver/Type = FETI or Auto) or by Solver/Outer Algorithm = "
                         << kSemismooth << ", not by Solver/Type = Monolithic");
      // Which algorithms solve which law: the registry's compatibility query.
      auto solves = [&](const std::string& algorithm) {
        return algorithm == kSemismooth ? law != FrictionLaw::Coulomb
                                        : Friction::frictionSolvers().accepts(algorithm, frictionLawName(law));
      };
      std::string able;
      for (const auto& a : outerAlgorithms()) if (solves(a)) able += (able.empty() ? "" : " or ") + a;
      TRIBOS_REQUIRE(solves(outer), "Contact/Friction Law = " << frictionLawName(law) << " needs Solver/Outer Algorithm = " << able
                                                              << ", not " << outer);
      if (outer != kSemismooth) checkOuterAlgorithm(outer, solver);
      else checkSemismooth(solver.sublist(kSemismooth));
    }
    const auto& vf = params.sublist("Boundary Conditions").get<Array<double>>("Volume Force");
    TRIBOS_REQUIRE(vf.size() == 3, "\"Boundary Conditions/Volume Force\" needs 3 components");
    requireFinite(params, "");
    validateDynamics(params);
    validateLoadHistory(params);
    validateStepSolvers(params);
    validateMaterial(params.sublist("Material"));
    validateOutput(params.sublist("Output"));
    validateProblemName(params.get<std::string>("Problem Name"));
    validateFaceNames(params);
    boxSpec(params);  // cell and node counts fit
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  } catch (const std::exception& e) {
    throw Error(source + ": " + cleanTeuchosMessage(e.what()));
  }
}

void applyOverride(ParameterList& params, const std::string& assignment) {
  // The characters an input file may hold (XML 1.0 text in UTF-8), before the text is quoted in any message.
  IO::checkText(assignment, "--set \"" + IO::visibleText(assignment) + "\"");
  const auto eq = assignment.find('=');
  TRIBOS_REQUIRE(eq != std::string::npos && eq > 0, "--set \"" << assignment << "\": expected \"Sublist/Key=value\"");
  const std::string path = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  // Every component named: "Mesh/Level/" or "Mesh//Level" is a typo, not Mesh/Level.
  std::vector<std::string> parts;
  for (size_t begin = 0;;) {
    const size_t slash = path.find('/', begin);
    parts.push_back(path.substr(begin, slash == std::string::npos ? std::string::npos : slash - begin));
    TRIBOS_REQUIRE(!parts.back().empty(), "--set \"" << assignment << "\": \"" << path
                                                      << "\" has an empty component; expected \"Sublist/Key=value\"");
    if (slash == std::string::npos) break;
    begin = slash + 1;
  }
  ParameterList* user = &params;
  const ParameterList* valid = validParameters().get();
  std::string at;  // path of the current level
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (at == "Boundary Conditions/Dirichlet" || at == "Boundary Conditions/Traction") {
      valid = at == "Boundary Conditions/Dirichlet" ? &dirichletItem() : &tractionItem();
    } else if (at == "Load Curves") {
      valid = &curveItem();
    } else if (at == "Contact/Pairs" || at == "Bodies") {
      // Any name; typed as the item (its defaults do not matter here).
      static const ParameterList pair = pairItem(validParameters()->sublist("Contact"));
      static const ParameterList body = bodyItem(validParameters()->sublist("Material"));
      valid = at == "Bodies" ? &body : &pair;
    } else {
      TRIBOS_REQUIRE(valid->isSublist(p), "--set \"" << assignment << "\": no sublist \"" << p
                                                     << "\"; valid: " << joinNames(*valid));
      valid = &valid->sublist(p);
    }
    at += (at.empty() ? "" : "/") + p;
    user = &user->sublist(p);
  }
  const std::string& key = parts.back();
  TRIBOS_REQUIRE(at != "Boundary Conditions/Dirichlet" && at != "Boundary Conditions/Traction" &&
                     at != "Contact/Pairs" && at != "Bodies" && at != "Load Curves",
                 "--set \"" << assignment << "\": name a key inside a condition, pair, body or curve, e.g. \"" << path
                             << "/NAME/...\"");
  TRIBOS_REQUIRE(valid->isParameter(key) && !valid->isSublist(key),
                 "--set \"" << assignment << "\": unknown parameter \"" << path << "\"; valid: " << joinNames(*valid));
  const std::string type = IO::parameterTypeName(valid->getEntry(key).getAny());
  TRIBOS_REQUIRE(!type.empty(), "--set \"" << assignment << "\": \"" << path << "\" cannot be set from the command line");
  IO::setParsedParameter(*user, key, type, value, "--set: parameter \"" + path + "\"");
}

RCP<ParameterList> read(const std::string& file, const std::vector<std::string>& overrides) {
  RCP<ParameterList> params = IO::readParameterFile(file);
  for (const auto& o : overrides) applyOverride(*params, o);
  validate(*params, "input file \"" + file + "\"");
  // A mesh file relative to the input file's directory becomes absolute, so
  // that the effective parameters (BASE.parameters.xml in the output
  // directory, --print-parameters) run again from anywhere.
  auto& mesh = params->sublist("Mesh");
  const std::filesystem::path meshPath = mesh.get<std::string>("File");
  if (!meshPath.empty() && meshPath.is_relative())
    // (absolute first: a file named without a directory has an empty parent)
    mesh.set("File", (std::filesystem::absolute(file).parent_path() / meshPath)
                         .lexically_normal()
                         .string());
  // A .geo is a program: refused before any work unless the input opts in.
  Mesh::requireGeoScriptAllowed(meshFile(*params), meshFileOptions(*params, 0));
  return params;
}

std::string meshFile(const ParameterList& params) { return params.sublist("Mesh").get<std::string>("File"); }

Mesh::MeshFileOptions meshFileOptions(const ParameterList& params, double memoryLimit) {
  const auto& m = params.sublist("Mesh");
  Mesh::MeshFileOptions options;
  options.runGeoScript = m.get<bool>("Run Geo Script");
  options.geoTimeLimit = m.get<double>("Geo Time Limit");
  options.memoryLimit = memoryLimit;
  return options;
}

Mesh::Mesh mesh(const ParameterList& params, std::vector<std::string>* warnings, double memoryLimit) {
  const std::string file = meshFile(params);
  return file.empty() ? Mesh::generateBox(boxSpec(params))
                      : Mesh::readMeshFile(file, warnings, meshFileOptions(params, memoryLimit));
}

namespace {

double maxAbs(const Array<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// The diagonal of the mesh's bounding box.
double meshExtent(const Mesh::Mesh& mesh) {
  const auto box = Mesh::boundingBox(mesh);
  return std::hypot(box.x[1] - box.x[0], box.y[1] - box.y[0], box.z[1] - box.z[0]);
}

// A scale the solver forms products of: within [kMinScale, kMaxScale], or
// exactly 0 where the quantity may vanish (a load or a length; nonzero, it
// must be representable too: a load of 1e-300 is not zero to the solver,
// and its products underflow).
void requireScale(double scale, bool mayVanish, const std::string& what) {
  const bool above = scale > kMaxScale;
  TRIBOS_REQUIRE(!above && (scale >= kMinScale || (mayVanish && scale == 0)),
                 what << " is " << (above ? "above " : "below ") << (above ? kMaxScale : kMinScale)
                      << ": beyond the scales whose products double precision represents; state the problem in "
                         "other units (e.g. mm and MPa) or correct the value");
}

std::string quoted(const std::string& path, double value) {
  std::ostringstream os;
  os << "\"" << path << "\" = " << value;
  return os.str();
}

// A load at one step: its Value times its curve ("": the ramp min(t, 1)) at
// the step time t. What names it beside its path: the curve, the factor and
// the time, unless the factor is 1 without a curve (the static problem).
std::string stepText(const std::string& curve, double t, double factor) {
  if (curve.empty() && factor == 1) return "";
  std::ostringstream os;
  os << " times " << (curve.empty() ? std::string("the ramp min(t, 1)") : "\"Load Curves/" + curve + "\"") << " ("
     << factor << " at the step time " << t << ")";
  return os.str();
}

// check(scale x |curve(t)|, stepText) at every step time t: a load's scale
// at each step of the run, whether its curve or the ramp scales it.
template <class Check>
void atEveryStep(const ParameterList& params, const std::string& curveName, double scale, Check check) {
  const Fem::LoadCurve curve = loadCurve(params, curveName);
  for (double t : loadStepTimes(params)) {
    const double factor = curve(t);
    check(scale * std::abs(factor), stepText(curveName, t, factor));
  }
}

}  // namespace

void checkScales(const ParameterList& params, const Mesh::Mesh& mesh) {
  const double L = meshExtent(mesh);
  std::ostringstream extent;
  extent << " with a mesh of extent L = " << L;
  // Stiffness: every material the mesh uses (Material unless every body has its own).
  std::vector<std::pair<std::string, double>> moduli = {
      {"Material/Young's Modulus", params.sublist("Material").get<double>("Young's Modulus")}};
  const auto& bodies = params.sublist("Bodies");
  for (auto it = bodies.begin(); it != bodies.end(); ++it)
    moduli.emplace_back("Bodies/" + bodies.name(it) + "/Material/Young's Modulus",
                        bodies.sublist(bodies.name(it)).sublist("Material").get<double>("Young's Modulus"));
  double softest = moduli.front().second;
  for (const auto& [path, E] : moduli) {
    std::ostringstream os;
    os << quoted(path, E) << extent.str() << " gives a stiffness scale E L = " << E * L;
    requireScale(E * L, false, os.str());
    softest = std::min(softest, E);
  }
  // Loads at every step: their resultant over the mesh, and the displacement
  // they cause in the softest material.
  auto requireLoad = [&](const std::string& name, double resultant) {
    std::ostringstream os;
    os << name << extent.str() << " gives a resultant force of about " << resultant;
    requireScale(resultant, true, os.str());
    os << " and a displacement of about " << resultant / (softest * L) << " in the softest material";
    requireScale(resultant / (softest * L), true, os.str());
  };
  const auto& bc = params.sublist("Boundary Conditions");
  const std::string volumeCurve = bc.get<std::string>("Volume Force Curve");
  atEveryStep(params, volumeCurve, maxAbs(bc.get<Array<double>>("Volume Force")) * L * L * L,
              [&](double resultant, const std::string& step) {
                requireLoad("\"Boundary Conditions/Volume Force\"" + step, resultant);
              });
  const auto& tractions = bc.sublist("Traction");
  for (auto it = tractions.begin(); it != tractions.end(); ++it) {
    const auto& item = tractions.sublist(tractions.name(it));
    atEveryStep(params, item.get<std::string>("Curve"), maxAbs(item.get<Array<double>>("Value")) * L * L,
                [&](double resultant, const std::string& step) {
                  requireLoad("\"Boundary Conditions/Traction/" + tractions.name(it) + "/Value\"" + step, resultant);
                });
  }
  // The Tresca slip bounds act as loads where the contact slips (the same at every step).
  const auto& contact = params.sublist("Contact");
  const auto& pairs = contact.sublist("Pairs");
  requireLoad("\"Contact/Slip Bound Traction\"", contact.get<double>("Slip Bound Traction") * L * L);
  for (auto it = pairs.begin(); it != pairs.end(); ++it)
    requireLoad("\"Contact/Pairs/" + pairs.name(it) + "/Slip Bound Traction\"",
                pairs.sublist(pairs.name(it)).get<double>("Slip Bound Traction") * L * L);
  // Lengths: prescribed displacements (at every step), gaps, plane points.
  const auto& dirichlet = bc.sublist("Dirichlet");
  for (auto it = dirichlet.begin(); it != dirichlet.end(); ++it) {
    const std::string path = "Boundary Conditions/Dirichlet/" + dirichlet.name(it) + "/Value";
    const auto& item = dirichlet.sublist(dirichlet.name(it));
    const double u = maxAbs(item.get<Array<double>>("Value"));
    atEveryStep(params, item.get<std::string>("Curve"), u, [&](double scale, const std::string& step) {
      requireScale(scale, true, quoted(path, u) + " (its largest component)" + step);
    });
  }
  requireScale(std::abs(contact.get<double>("Gap")), true, quoted("Contact/Gap", contact.get<double>("Gap")));
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const std::string path = "Contact/Pairs/" + pairs.name(it) + "/Plane Point";
    const double x = maxAbs(pairs.sublist(pairs.name(it)).get<Array<double>>("Plane Point"));
    requireScale(x, true, quoted(path, x) + " (its largest component)");
  }
}

namespace {

// Contact on second-order surfaces is mortar's (its transformed basis,
// Tribos_Mortar.hpp) or a rigid plane's, through FETI: a node-to-segment
// pair between two bodies whose slave surface lies on second-order cells
// (surfaceType(name) the type of the cells under a face) is refused, naming
// it, and on a mesh (`where`) with second-order cells so is the semismooth*
// method, whose rows are nodal (a corner's lumped area is zero or negative).
void requireMortarOnSecondOrder(const std::vector<Mesh::CellType>& cellTypes,
                                const std::function<Mesh::CellType(const std::string&)>& surfaceType,
                                const std::string& where, const ParameterList& params) {
  const auto& contact = params.sublist("Contact");
  if (!contact.get<bool>("Enabled")) return;
  for (Mesh::CellType type : cellTypes)
    TRIBOS_REQUIRE(!Mesh::isSecondOrder(type) || method(params) != Method::Semismooth,
                   "Solver/Outer Algorithm = " << kSemismooth << ": " << where << " has " << Mesh::cellTypeName(type)
                                               << " cells; the method's contact rows are nodal, and the corner nodes of "
                                                  "second-order facets have no positive area (use FETI's algorithms)");
  const auto& pairs = contact.sublist("Pairs");
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const std::string name = pairs.name(it);
    const auto& p = pairs.sublist(name);
    const std::string master = p.get<std::string>("Master Surface"), slave = p.get<std::string>("Slave Surface");
    if (master.empty() || p.get<std::string>("Discretization") != "Node To Segment") continue;
    const Mesh::CellType type = surfaceType(slave);
    if (!Mesh::isSecondOrder(type)) continue;
    throw Error("parameter \"Contact/Pairs/" + name + "/Discretization\" = \"Node To Segment\" (slave surface '" +
                slave + "', master surface '" + master + "'): " + where + " has " + Mesh::cellTypeName(type) +
                " cells under the slave surface, whose facets are " +
                (type == Mesh::CellType::Tet10 ? "6-node triangles" : "8-node quadrilaterals") +
                "; their corner nodes take no share, or a negative one, of a uniform pressure, which one "
                "node-to-segment row per node cannot transmit: use \"Mortar\" (the default)");
  }
}

}  // namespace

void checkMeshFaces(const Mesh::Mesh& mesh, const ParameterList& params) {
  const std::string file = meshFile(params);
  const std::string where = file.empty() ? "the box" : "mesh file \"" + file + "\"";
  std::string names;
  for (const auto& n : mesh.faceNames()) names += (names.empty() ? "" : ", ") + n;
  for (const auto& [path, face] : namedFaces(params))
    TRIBOS_REQUIRE(mesh.faces.count(face) || (mesh.nodeSets.count(face) && path.find("Dirichlet") != std::string::npos),
                   "parameter \"" << path << "\" = \"" << face << "\": " << where
                                  << " has no " << (mesh.nodeSets.count(face) ? "face (only a node set, which carries "
                                                                                 "Dirichlet conditions only) "
                                                                               : "physical surface ")
                                  << "of that name; its names are: " << (names.empty() ? "(none)" : names));
  const auto& bodies = params.sublist("Bodies");
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    std::string valid;
    bool found = false;
    for (int b = 0; b < mesh.numBodies(); ++b)
      found = found || mesh.bodyName(b) == bodies.name(it), valid += (valid.empty() ? "" : ", ") + mesh.bodyName(b);
    TRIBOS_REQUIRE(found, "parameter \"Bodies/" << bodies.name(it) << "\": " << where << " has no body of that name; "
                                                << "its bodies are: " << valid);
  }
  if (dynamics(params)) {
    // Every body's density: its own, or Material's for a body not named.
    const double common = params.sublist("Material").get<double>("Density");
    for (int b = 0; b < mesh.numBodies(); ++b)
      TRIBOS_REQUIRE(bodies.isSublist(mesh.bodyName(b)) || common > 0,
                     "body \"" << mesh.bodyName(b) << "\" of " << where << " has no density: Dynamics needs rho > 0 "
                                << "from \"Bodies/" << mesh.bodyName(b) << "/Material/Density\" or \"Material/Density\" (= "
                                << common << ")");
  }
  // The type of the cells under a face (one body's: every body has one type).
  const auto surfaceType = [&](const std::string& face) {
    const auto& facets = mesh.faces.count(face) ? mesh.face(face) : std::vector<Mesh::Facet>();
    return facets.empty() ? Mesh::CellType::Tet4 : mesh.cellType(facets.front().cell);
  };
  requireMortarOnSecondOrder(mesh.cellTypesPresent(), surfaceType, where, params);
}

namespace {

// Cells along one axis from Level: k cells per unit length, computed in
// floating point so that a huge extent is refused instead of wrapping round.
int cellsFromLevel(int level, double length, char axis) {
  const double cells = std::max(1.0, std::round(level * length));
  TRIBOS_REQUIRE(cells <= Mesh::kMaxCellsPerAxis, "\"Mesh/Level\" = " << level << " gives " << cells << " cells along "
                                                                       << axis << " (extent " << length << "); at most "
                                                                       << Mesh::kMaxCellsPerAxis << " are allowed");
  return static_cast<int>(cells);
}

}  // namespace

Mesh::BoxSpec boxSpec(const ParameterList& params) {
  const auto& m = params.sublist("Mesh");
  Mesh::BoxSpec spec;
  spec.type = Mesh::cellTypeFromName(m.get<std::string>("Element"));
  const auto& x = m.get<Array<double>>("X Range");
  const auto& y = m.get<Array<double>>("Y Range");
  const auto& z = m.get<Array<double>>("Z Range");
  spec.x = {x[0], x[1]};
  spec.y = {y[0], y[1]};
  spec.z = {z[0], z[1]};
  const int level = m.get<int>("Level");
  if (level == 0) {
    const auto& c = m.get<Array<int>>("Cells");
    for (int a = 0; a < 3; ++a) {
      TRIBOS_REQUIRE(c[a] <= Mesh::kMaxCellsPerAxis, "\"Mesh/Cells\" = " << c[a] << " along " << "xyz"[a] << ": at most "
                                                                         << Mesh::kMaxCellsPerAxis << " are allowed");
      spec.cells[a] = c[a];
    }
  } else if (m.get<std::string>("Level Rule") == "Prism") {
    spec.cells = Mesh::prismLevelCells(level);
  } else {
    const double len[3] = {x[1] - x[0], y[1] - y[0], z[1] - z[0]};
    for (int a = 0; a < 3; ++a) spec.cells[a] = cellsFromLevel(level, len[a], "xyz"[a]);
  }
  // Node and cell numbers are ints: refuse what does not fit (the memory
  // estimate refuses most such meshes anyway, with the bytes it would need).
  const double nodes = Mesh::boxNodeCount(spec), cells = Mesh::boxCellCount(spec);
  TRIBOS_REQUIRE(nodes * 3 < 2147483647.0 && cells < 2147483647.0,
                 "Mesh: " << spec.cells[0] << " x " << spec.cells[1] << " x " << spec.cells[2] << " cells (" << nodes
                          << " nodes) exceed the 2^31 - 1 degrees of freedom and cells a mesh may have");
  // The coordinates every mesh reader checks, and contact on its cells, here
  // for the box before any work.
  if (meshFile(params).empty()) {
    Mesh::requireUsableBox(spec, "the box (Mesh/X Range, Y Range, Z Range)");
    requireMortarOnSecondOrder({spec.type}, [&](const std::string&) { return spec.type; },
                               "the box (\"Mesh/Element\" = \"" + Mesh::cellTypeName(spec.type) + "\")", params);
  }
  return spec;
}

bool dynamics(const ParameterList& params) { return params.sublist("Dynamics").get<bool>("Enabled"); }

bool fetiContact(const ParameterList& params) {
  return method(params) == Method::FetiContact || (dynamics(params) && params.sublist("Contact").get<bool>("Enabled"));
}

Contact::DynamicsSpec dynamicsSpec(const ParameterList& params) {
  const auto& d = params.sublist("Dynamics");
  Contact::DynamicsSpec spec;
  spec.timeStep = d.get<double>("Time Step");
  spec.scheme = Contact::timeSchemeFromName(d.get<std::string>("Scheme"));
  const auto& v = params.sublist("Initial Conditions").get<Array<double>>("Velocity");
  spec.initialVelocity = {v[0], v[1], v[2]};
  return spec;
}

Contact::DynamicsSpec dynamicsSpec(const ParameterList& params, const Mesh::Mesh& mesh) {
  Contact::DynamicsSpec spec = dynamicsSpec(params);
  spec.bodyVelocity = initialVelocities(params, mesh);
  return spec;
}

std::vector<std::array<double, 3>> initialVelocities(const ParameterList& params, const Mesh::Mesh& mesh) {
  const auto& global = params.sublist("Initial Conditions").get<Array<double>>("Velocity");
  std::vector<std::array<double, 3>> perBody(mesh.numBodies(), {global[0], global[1], global[2]});
  const auto& bodies = params.sublist("Bodies");
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    const auto& own = bodies.sublist(bodies.name(it)).get<Array<double>>("Initial Velocity");
    if (!own.empty()) perBody[mesh.bodyIndex(bodies.name(it))] = {own[0], own[1], own[2]};
  }
  return perBody;
}

namespace {

// The parameter that gives a body its initial velocity, for a message.
std::string velocityParameter(const ParameterList& params, const std::string& body) {
  const auto& bodies = params.sublist("Bodies");
  const bool own = bodies.isSublist(body) && !bodies.sublist(body).get<Array<double>>("Initial Velocity").empty();
  return own ? "\"Bodies/" + body + "/Initial Velocity\"" : "\"Initial Conditions/Velocity\" (body \"" + body + "\")";
}

std::string vectorText(const std::array<double, 3>& v) {
  std::ostringstream os;
  os << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return os.str();
}

}  // namespace

void checkBondedVelocities(const Mesh::Mesh& mesh, const ParameterList& params) {
  if (!dynamics(params) || mesh.numBodies() < 2) return;
  const auto velocity = initialVelocities(params, mesh);
  // The first body met at each node; a cell of another body with another
  // velocity there makes the node a bonded one whose copies would start
  // apart (they are glued: the first step would tear the jump off).
  std::vector<int> nodeBody(mesh.numNodes(), -1);
  std::vector<char> counted(mesh.numNodes(), 0);
  int first = -1, a = -1, b = -1;  // the first such node and its bodies
  long long count = 0;
  for (int c = 0; c < mesh.numCells(); ++c)
    for (int k = 0; k < mesh.cellSize(c); ++k) {
      const int n = mesh.cell(c)[k], body = mesh.bodyOf(c);
      if (nodeBody[n] < 0) nodeBody[n] = body;
      if (velocity[nodeBody[n]] == velocity[body] || counted[n]) continue;
      counted[n] = 1;
      ++count;
      if (first < 0) first = n, a = nodeBody[n], b = body;
    }
  if (first < 0) return;
  std::ostringstream os;
  os << "bodies \"" << mesh.bodyName(a) << "\" and \"" << mesh.bodyName(b) << "\" share node " << first << " at "
     << vectorText(mesh.coords[first]) << " (" << count << " such node(s)), but "
     << velocityParameter(params, mesh.bodyName(a)) << " = " << vectorText(velocity[a]) << " and "
     << velocityParameter(params, mesh.bodyName(b)) << " = " << vectorText(velocity[b])
     << ": bodies bonded through shared nodes move as one; give them the same initial velocity, or distinct nodes "
        "joined by contact";
  throw Error(os.str());
}

int stepStride(const ParameterList& params) { return params.sublist("Output").get<int>("Step Stride"); }

Fem::BodyDensities densities(const ParameterList& params, const Mesh::Mesh& mesh) {
  const auto& bodies = params.sublist("Bodies");
  std::vector<double> perBody(mesh.numBodies(), params.sublist("Material").get<double>("Density"));
  for (auto it = bodies.begin(); it != bodies.end(); ++it)
    perBody[mesh.bodyIndex(bodies.name(it))] = bodies.sublist(bodies.name(it)).sublist("Material").get<double>("Density");
  return Fem::BodyDensities(std::move(perBody));
}

Method method(const ParameterList& params) {
  const auto& solver = params.sublist("Solver");
  if (dynamics(params)) return Method::FetiDynamics;
  if (!params.sublist("Contact").get<bool>("Enabled"))
    return solver.get<std::string>("Type") == "FETI" ? Method::FetiLinear : Method::Monolithic;
  return solver.get<std::string>("Outer Algorithm") == "SemismoothStarNewton" ? Method::Semismooth : Method::FetiContact;
}

std::array<int, 3> subdomainGridOfSize(const std::array<int, 3>& cells, int H) {
  std::array<int, 3> grid{1, 1, 1};
  for (int a = 0; a < 3; ++a) {
    // The divisor d of cells[a] whose boxes (cells[a] / d cells) are nearest
    // to H cells; ties go to the larger boxes.
    double best = 1e300;
    for (int d = 1; d <= cells[a]; ++d) {
      if (cells[a] % d != 0) continue;
      const double miss = std::abs(std::log(double(cells[a]) / d / H));
      if (miss < best - 1e-12) best = miss, grid[a] = d;
    }
  }
  return grid;
}

SubdomainSizing subdomainSizing(const ParameterList& params) {
  const std::string text = params.sublist("Mesh").get<std::string>("Subdomain Size");
  SubdomainSizing sizing;
  if (text == "Grid" || text == "0") return sizing;
  if (text == "Auto") {
    sizing.kind = SubdomainSizing::Auto;
    return sizing;
  }
  // A positive integer, parsed completely ("4x" and "4.5" are refused).
  int H = 0;
  std::string why;
  TRIBOS_REQUIRE(IO::parseInt(text, H, why) && H >= 1 && H <= 1000000,
                 "parameter \"Mesh/Subdomain Size\" = \"" << text
                                                           << "\": expected Grid, Auto or a whole number of cells in "
                                                              "[1, 1000000]");
  sizing.kind = SubdomainSizing::Fixed;
  sizing.H = H;
  return sizing;
}

Mesh::DecompositionSpec decompositionSpec(const ParameterList& params, int numRanks, const MeshSize* meshSize) {
  const auto& m = params.sublist("Mesh");
  Mesh::DecompositionSpec dec;
  dec.partitioner = m.get<std::string>("Partitioner");
  const auto& g = m.get<Array<int>>("Subdomain Grid");
  dec.grid = {g[0], g[1], g[2]};
  dec.subdomains = m.get<int>("Subdomains");
  const SubdomainSizing sizing = subdomainSizing(params);
  if (sizing.kind != SubdomainSizing::Grid && meshFile(params).empty()) {
    const auto cells = boxSpec(params).cells;
    auto countOf = [&](int H) {
      const auto grid = subdomainGridOfSize(cells, H);
      return double(grid[0]) * grid[1] * grid[2];
    };
    dec.size = sizing.kind == SubdomainSizing::Fixed ? sizing.H : automaticSubdomainSize(countOf, numRanks);
    dec.grid = subdomainGridOfSize(cells, dec.size);
    dec.subdomains = dec.grid[0] * dec.grid[1] * dec.grid[2];  // METIS: as many subdomains of about that size
    return dec;
  }
  if (sizing.kind != SubdomainSizing::Grid) {
    // METIS parts of about (H+1)^3 nodes, as the box's subdomains of size H;
    // at least one per rank and per body (METIS cuts each body on its own),
    // at most one per cell. Unknown (0) until the file is read.
    dec.partitioner = "METIS";
    dec.subdomains = 0;
    if (!meshSize) return dec;
    auto countOf = [&](int H) { return std::max(1.0, std::round(meshSize->nodes / std::pow(H + 1.0, 3))); };
    dec.size = sizing.kind == SubdomainSizing::Fixed
                   ? sizing.H
                   : automaticMeshFileSubdomainSize(meshSize->nodes, countOf, numRanks);
    const double least = std::max(double(numRanks), double(meshSize->bodies));
    dec.subdomains = static_cast<int>(std::min(std::max(countOf(dec.size), least), meshSize->cells));
    return dec;
  }
  // A grid of boxes splits a box only: a mesh from a file is split by METIS
  // into as many subdomains as the grid has boxes (so that an input file's
  // default, Structured {1, 1, 1}, stays valid).
  if (!meshFile(params).empty() && dec.partitioner == "Structured") {
    dec.partitioner = "METIS";
    dec.subdomains = dec.grid[0] * dec.grid[1] * dec.grid[2];
  }
  return dec;
}

Fem::Material material(const ParameterList& params) {
  const auto& m = params.sublist("Material");
  Fem::Material mat;
  mat.E = m.get<double>("Young's Modulus");
  mat.nu = m.get<double>("Poisson's Ratio");
  return mat;
}

Fem::LoadCase loadCase(const ParameterList& params) {
  const auto& bc = params.sublist("Boundary Conditions");
  Fem::LoadCase loads;
  const auto& d = bc.sublist("Dirichlet");
  for (auto it = d.begin(); it != d.end(); ++it) {
    const auto& item = d.sublist(d.name(it));
    Fem::DirichletCondition c;
    c.face = item.get<std::string>("Face");
    const std::string comps = item.get<std::string>("Components");
    for (int k = 0; k < 3; ++k) c.fix[k] = comps.find("xyz"[k]) != std::string::npos;
    const auto& v = item.get<Array<double>>("Value");
    c.value = {v[0], v[1], v[2]};
    loads.dirichlet.push_back(c);
  }
  const auto& t = bc.sublist("Traction");
  for (auto it = t.begin(); it != t.end(); ++it) {
    const auto& item = t.sublist(t.name(it));
    const auto& v = item.get<Array<double>>("Value");
    loads.tractions.push_back({item.get<std::string>("Face"), {v[0], v[1], v[2]}});
  }
  const auto& vf = bc.get<Array<double>>("Volume Force");
  loads.volumeForce = {vf[0], vf[1], vf[2]};
  return loads;
}

std::vector<double> loadStepTimes(const ParameterList& params) {
  if (dynamics(params)) {
    const auto& d = params.sublist("Dynamics");
    const double dt = d.get<double>("Time Step");
    const long long steps = std::llround(d.get<double>("End Time") / dt);
    std::vector<double> times;
    for (long long k = 1; k <= steps; ++k) times.push_back(static_cast<double>(k) * dt);
    return times;
  }
  if (!params.isSublist("Load Steps")) return {1.0};
  const auto& times = params.sublist("Load Steps").get<Array<double>>("Times");
  return std::vector<double>(times.begin(), times.end());
}

Fem::LoadCurve loadCurve(const ParameterList& params, const std::string& name) {
  if (name.empty()) return Fem::LoadCurve();
  const auto& curves = params.sublist("Load Curves");
  TRIBOS_REQUIRE(curves.isSublist(name), "Load Curves defines no curve \"" << name << "\"");
  const auto& curve = curves.sublist(name);
  const auto& t = curve.get<Array<double>>("Times");
  const auto& v = curve.get<Array<double>>("Values");
  return Fem::LoadCurve({t.begin(), t.end()}, {v.begin(), v.end()}, "\"Load Curves/" + name + "\"");
}

Fem::LoadHistory loadHistory(const ParameterList& params) {
  Fem::LoadHistory history;
  history.base = loadCase(params);
  const auto& bc = params.sublist("Boundary Conditions");
  auto curvesOf = [&](const ParameterList& items) {
    std::vector<Fem::LoadCurve> curves;
    for (auto it = items.begin(); it != items.end(); ++it)
      curves.push_back(loadCurve(params, items.sublist(items.name(it)).get<std::string>("Curve")));
    return curves;
  };
  // In a Dynamics run a load without a Curve is constant from t = 0.
  if (dynamics(params)) {
    const double end = params.sublist("Dynamics").get<double>("End Time");
    const Fem::LoadCurve constant({0.0, std::max(end, 1.0) * 2}, {1.0, 1.0}, "a load without a Curve (constant)");
    const auto orConstant = [&](std::vector<Fem::LoadCurve> curves) {
      for (auto& c : curves)
        if (c.isRamp()) c = constant;
      return curves;
    };
    history.dirichletCurves = orConstant(curvesOf(bc.sublist("Dirichlet")));
    history.tractionCurves = orConstant(curvesOf(bc.sublist("Traction")));
    history.volumeForceCurve = orConstant({loadCurve(params, bc.get<std::string>("Volume Force Curve"))}).front();
    return history;
  }
  history.dirichletCurves = curvesOf(bc.sublist("Dirichlet"));
  history.tractionCurves = curvesOf(bc.sublist("Traction"));
  history.volumeForceCurve = loadCurve(params, bc.get<std::string>("Volume Force Curve"));
  return history;
}

Fem::LoadCase loadCaseAt(const ParameterList& params, double t) { return Fem::loadCaseAt(loadHistory(params), t); }

PlaneContact planeContact(const ParameterList& params) {
  const auto& contact = params.sublist("Contact");
  PlaneContact pc;
  pc.face = contact.get<std::string>("Face");
  pc.gap = contact.get<double>("Gap");
  pc.law = frictionLaw(contact, "Friction Law");
  // Frictionless: slip bound 0 whatever Slip Bound Traction says.
  pc.slipBoundTraction = pc.law == FrictionLaw::Frictionless ? 0.0 : contact.get<double>("Slip Bound Traction");
  return pc;
}

// The largest component of a prescribed displacement at any step (the load
// scale of Contact::automaticSearchDistance).
double largestPrescribedDisplacement(const ParameterList& params) {
  double largest = 0;
  const auto& dirichlet = params.sublist("Boundary Conditions").sublist("Dirichlet");
  for (auto it = dirichlet.begin(); it != dirichlet.end(); ++it) {
    const auto& item = dirichlet.sublist(dirichlet.name(it));
    atEveryStep(params, item.get<std::string>("Curve"), maxAbs(item.get<Array<double>>("Value")),
                [&](double scale, const std::string&) { largest = std::max(largest, scale); });
  }
  return largest;
}

std::vector<Contact::ContactPair> contactPairs(const ParameterList& params, const Mesh::Mesh& mesh) {
  const auto& contact = params.sublist("Contact");
  if (!contact.get<bool>("Enabled")) return {};
  const auto& pairs = contact.sublist("Pairs");
  if (pairs.numParams() == 0)
    return {Contact::planeBeyondFace(mesh, contact.get<std::string>("Face"), contact.get<double>("Gap"))};
  std::vector<Contact::ContactPair> out;
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const auto& p = pairs.sublist(pairs.name(it));
    Contact::ContactPair pair;
    pair.name = pairs.name(it);
    pair.slave = p.get<std::string>("Slave Surface");
    pair.master = p.get<std::string>("Master Surface");
    pair.glued = p.get<std::string>("Type") == "Glued";
    const auto& x = p.get<Array<double>>("Plane Point");
    const auto& n = p.get<Array<double>>("Plane Normal");
    const double length = norm(Vec3{n[0], n[1], n[2]});
    for (int d = 0; d < 3; ++d) pair.planePoint[d] = x[d], pair.planeNormal[d] = n[d] / length;
    pair.discretization = Contact::discretizationValidator()->getIntegralValue(p.get<std::string>("Discretization"));
    const double reach = p.get<double>("Search Distance");
    pair.automaticSearch = reach == 0;
    pair.searchDistance = reach > 0 ? reach
                                    : Contact::automaticSearchDistance(mesh, pair.slave, largestPrescribedDisplacement(params));
    out.push_back(pair);
  }
  return out;
}

Contact::PairFriction pairFriction(const ParameterList& params) {
  auto spec = [](const ParameterList& list) {
    Contact::FrictionSpec f;
    f.law = frictionLaw(list, "Friction Law");
    f.coefficient = list.get<double>("Friction Coefficient");
    f.slipBoundTraction = list.get<double>("Slip Bound Traction");
    return f;
  };
  const auto& contact = params.sublist("Contact");
  const auto& pairs = contact.sublist("Pairs");
  if (pairs.numParams() == 0) return {spec(contact)};
  Contact::PairFriction out;
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const auto& p = pairs.sublist(pairs.name(it));
    out.push_back(p.get<std::string>("Type") == "Glued" ? Contact::FrictionSpec() : spec(p));
  }
  return out;
}

Fem::BodyMaterials materials(const ParameterList& params, const Mesh::Mesh& mesh) {
  const auto& bodies = params.sublist("Bodies");
  std::vector<Fem::Material> perBody(mesh.numBodies(), material(params));
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    const auto& m = bodies.sublist(bodies.name(it)).sublist("Material");
    Fem::Material& mat = perBody[mesh.bodyIndex(bodies.name(it))];
    mat.E = m.get<double>("Young's Modulus");
    mat.nu = m.get<double>("Poisson's Ratio");
  }
  return Fem::BodyMaterials(std::move(perBody));
}

Semismooth::MeshContactProblem semismoothProblem(const ParameterList& params) {
  Semismooth::MeshContactProblem pr;
  pr.mesh = mesh(params);
  pr.material = material(params);
  pr.loads = loadCase(params);
  const PlaneContact pc = planeContact(params);
  pr.contactFace = pc.face;
  pr.gap = pc.gap;
  pr.slipBoundTraction = pc.slipBoundTraction;
  pr.solverParams = params.sublist("Solver").sublist(kSemismooth);
  return pr;
}

}  // namespace Input
}  // namespace Tribos
