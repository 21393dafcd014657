// Module-level tools: statics, wrap, the membrane fit, synthetic membrane data, the scene list.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/cable/wrap_io.h"
#include "engine/core/error.h"
#include "engine/core/parse.h"
#include "engine/membrane/membrane_data.h"
#include "engine/membrane/membrane_fit.h"
#include "engine/membrane/membrane_fit_io.h"
#include "engine/membrane/membrane_synth.h"
#include "engine/scenes/scene_registry.h"
#include "engine/statics/socp.h"
#include "engine/statics/statics.h"
#include "engine/statics/statics_io.h"
#include "engine/statics/statics_newton.h"
#include "python/bindings.h"

namespace cablelab::python {

namespace {

bool isPath(py::handle v) {
  return py::isinstance<py::str>(v) || py::hasattr(v, "__fspath__");
}

/// cables as a list of {"a", "b", "k", "L"} dicts, an (N, 6) array of ax ay bx by k L, or a
/// whole problem dict {"cables": ..., "p0": ...}: the statics input JSON.
nlohmann::json staticsJson(py::handle cables, py::handle p0) {
  nlohmann::json j;
  if (py::isinstance<py::dict>(cables)) {
    j = toJson(cables, "statics");
  } else if (py::isinstance<py::array>(cables) &&
             py::array(py::reinterpret_borrow<py::object>(cables)).ndim() == 2) {
    auto a = py::array_t<double, py::array::forcecast | py::array::c_style>::ensure(cables);
    if (!a || a.shape(1) != 6)
      throw InputError("statics", "cables",
                       "an array must be (N, 6): ax ay bx by k L per cable" + gotPython(cables));
    j["cables"] = nlohmann::json::array();
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
      const double* r = a.data(i, 0);
      nlohmann::json c;
      for (int k = 0; k < 6; ++k)
        if (!std::isfinite(r[k]))
          throw InputError("statics", "cables[" + std::to_string(i) + "]",
                           "must be finite" + gotValue(r[k]));
      c["a"] = {r[0], r[1]}, c["b"] = {r[2], r[3]}, c["k"] = r[4], c["L"] = r[5];
      j["cables"].push_back(c);
    }
  } else {
    j["cables"] = toJson(cables, "statics", "cables");
  }
  if (!p0.is_none()) j["p0"] = toJson(p0, "statics", "p0");
  return j;
}

py::dict staticsCall(py::handle cables, const std::string& solver, py::handle p0) {
  if (solver != "auto" && solver != "socp" && solver != "newton")
    throw InputError("--solver", "solver", "must be auto, socp or newton (got \"" + solver + "\")");
  StaticsProblem problem;
  if (isPath(cables)) {
    problem = loadStaticsFile(pathString(cables, "statics", "cables"));
    if (!p0.is_none()) problem.p0 = toVec2(p0, "statics", "p0");
  } else {
    problem = parseStaticsJson(staticsJson(cables, p0).dump(), "statics");
  }
  StaticsResult result;
  if (solver == "socp") {
    SocpWorkspace workspace;
    solveStaticsSocp(problem, result, workspace);
  } else if (solver == "newton") {
    solveStaticsNewton(problem, result);
  } else {
    solveStatics(problem, result);
  }
  // The CLI's JSON, so that both give the same keys; the vectors as numpy arrays.
  py::dict out = fromJson(nlohmann::json::parse(staticsResultToJson(result)));
  out["p"] = py::array_t<double>(2, result.p.data());
  out["lengths"] = py::array_t<double>(result.lengths.size(), result.lengths.data());
  out["tensions"] = py::array_t<double>(result.tensions.size(), result.tensions.data());
  return out;
}

py::dict wrapCall(py::handle a, py::handle b, py::handle polygon, py::handle side) {
  nlohmann::json j = nlohmann::json::object();  // None leaves a key out: "B: is required"
  const std::pair<const char*, py::handle> fields[] = {
      {"A", a}, {"B", b}, {"polygon", polygon}, {"side", side}};
  for (const auto& [key, value] : fields)
    if (!value.is_none()) j[key] = toJson(value, "wrap", key);
  const WrapSolution s = solveWrap(parseWrapJson(j, "wrap"), "wrap");
  py::dict out;
  out["path"] = pointsArray(s.path);
  out["length"] = s.length;
  out["contact_vertices"] = s.contacts;
  return out;
}

/// --pulleys as the CLI's text ("AX,AY,BX,BY": its parser and messages), 4 numbers or
/// [[AX, AY], [BX, BY]].
MembraneGeometry pulleysOf(py::handle pulleys) {
  if (py::isinstance<py::str>(pulleys))
    return membranePulleys(
        parseNumberList(pulleys.cast<std::string>(), 4, kCommandLine, "--pulleys", "AX,AY,BX,BY"));
  auto a = py::array_t<double, py::array::forcecast>::ensure(pulleys);
  if (!a || a.size() != 4)
    throw InputError(
        kCommandLine, "--pulleys",
        "must be AX, AY, BX, BY (m): 4 numbers or [[AX, AY], [BX, BY]]" + gotPython(pulleys));
  return membranePulleys(toNumbers(a.attr("reshape")(4), 4, kCommandLine, "--pulleys"));
}

std::vector<MembraneSample> membraneRows(py::handle data, const MembraneGeometry& g) {
  if (isPath(data)) return loadMembraneCsv(pathString(data, "fit", "data"), g);
  auto a = py::array_t<double, py::array::forcecast | py::array::c_style>::ensure(data);
  if (!a || a.ndim() != 2 || a.shape(1) != 4)
    throw InputError("data", "(array)",
                     "must be an (n, 4) array: x, y (m), fy (N), angle_deg per row, or a CSV path" +
                         gotPython(data));
  // Through the CSV reader, so an array is checked exactly as a file is (same messages).
  std::ostringstream csv;
  csv << "x,y,fy,angle_deg\n";
  char line[128];
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    const double* r = a.data(i, 0);
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g\n", r[0], r[1], r[2], r[3]);
    csv << line;
  }
  std::istringstream in(csv.str());
  return parseMembraneCsv(in, g, "data");
}

py::dict fitCall(py::handle data, py::handle pulleys, py::handle sigmaFy, py::handle sigmaAngle) {
  const MembraneGeometry g = pulleysOf(pulleys);
  MembraneFitOptions options;
  options.source = isPath(data) ? pathString(data, "fit", "data") : "data";
  if (!sigmaFy.is_none()) options.sigmaFy = membraneSigma(sigmaFy.cast<double>(), "--sigma-fy");
  if (!sigmaAngle.is_none())
    options.sigmaAngleDeg = membraneSigma(sigmaAngle.cast<double>(), "--sigma-angle-deg");
  const auto rows = membraneRows(data, g);
  const auto start = std::chrono::steady_clock::now();
  MembraneFitResult fit;
  {
    py::gil_scoped_release release;
    fit = fitMembrane(g, rows, options);
  }
  const double fitUs =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  py::dict out = fromJson(membraneFitJson(fit, options, fitUs));
  py::array_t<double> cov = newArray({2, 2});
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) cov.mutable_at(r, c) = fit.covariance(r, c);
  out["covariance"] = cov;
  return out;
}

py::array_t<double> samplesArray(const std::vector<MembraneSample>& rows) {
  py::array_t<double> a = newArray({static_cast<py::ssize_t>(rows.size()), 4});
  double* d = a.mutable_data();
  for (const MembraneSample& s : rows)
    *d++ = s.p.x(), *d++ = s.p.y(), *d++ = s.fy, *d++ = s.angleDeg;
  return a;
}

py::array_t<double> membraneDataCall(double k, double preload, py::handle pulleys, double noiseFy,
                                     double noiseAngle, long long seed, py::handle grid,
                                     py::handle depth, py::handle along) {
  MembraneSynthDef def;
  def.geometry = pulleysOf(pulleys);
  def.params.k = k, def.params.preload = preload;
  def.noiseFy = noiseFy, def.noiseAngleDeg = noiseAngle;
  if (seed < 0)
    throw InputError("membrane_data", "seed", "must be a whole number >= 0" + gotValue(seed));
  def.seed = static_cast<std::uint64_t>(seed);
  const auto g = toNumbers(grid, 2, "membrane_data", "grid");
  if (g[0] != std::floor(g[0]) || g[1] != std::floor(g[1]) || g[0] < 1 || g[1] < 1 ||
      g[0] * g[1] > 1e6)
    throw InputError("membrane_data", "grid",
                     "NX and NY must be whole numbers >= 1, at most 1e6 points (got (" +
                         formatNumber(g[0]) + ", " + formatNumber(g[1]) + "))");
  def.nx = static_cast<int>(g[0]), def.ny = static_cast<int>(g[1]);
  const auto d = toNumbers(depth, 2, "membrane_data", "depth");
  const auto a = toNumbers(along, 2, "membrane_data", "along");
  def.depthMin = d[0], def.depthMax = d[1], def.alongMin = a[0], def.alongMax = a[1];
  validateMembraneSynth(def, "membrane_data");
  return samplesArray(generateMembraneData(def));
}

py::dict membraneModelCall(py::handle pulleys, double k, double preload, py::handle points) {
  const MembraneGeometry g = pulleysOf(pulleys);
  auto a = py::array_t<double, py::array::forcecast | py::array::c_style>::ensure(points);
  if (!a || a.ndim() != 2 || a.shape(1) != 2)
    throw InputError("membrane_model", "points",
                     "must be an (n, 2) array of contact points (m)" + gotPython(points));
  const MembraneParams m{k, preload};
  const py::ssize_t n = a.shape(0);
  py::array_t<double> force = newArray({n, 2}), tension = newArray({n}), angle = newArray({n});
  for (py::ssize_t i = 0; i < n; ++i) {
    const Vec2 p(a.at(i, 0), a.at(i, 1));
    validateMembranePoint(g, p, static_cast<int>(i + 1), "membrane_model");
    const Vec2 f = membraneForce(g, m, p);
    force.mutable_at(i, 0) = f.x(), force.mutable_at(i, 1) = f.y();
    tension.mutable_at(i) = membraneTension(g, m, p);
    angle.mutable_at(i) = membraneForceAngleDeg(g, p);
  }
  py::dict out;
  out["force"] = force;
  out["tension"] = tension;
  out["angle_deg"] = angle;
  return out;
}

py::list scenesCall() {
  py::list out;
  for (const SceneInfo& s : builtinScenes()) {
    py::dict params;
    for (const SceneParam& p : s.params) {
      py::dict d;
      d["default"] = p.value;
      d["description"] = p.description;
      params[py::str(p.name)] = d;
    }
    py::dict d;
    d["name"] = s.name;
    d["description"] = s.description;
    d["params"] = params;
    out.append(d);
  }
  return out;
}

}  // namespace

void bindTools(py::module_& m) {
  using namespace pybind11::literals;
  m.def("statics", &staticsCall, "cables"_a, "solver"_a = "auto", "p0"_a = py::none(),
        R"doc(statics(cables, solver="auto", p0=None) -> dict

The equilibrium of a point held by cables (thesis 4.2), as `cablelab statics`: cable i
runs a_i -> p -> b_i with stiffness k_i (N/m) and rest length L_i (m), tension
k_i max(0, length - L_i). cables: a list of {"a": [x, y], "b": [x, y], "k": k, "L": L},
an (N, 6) array of ax ay bx by k L, the whole input dict {"cables": ..., "p0": ...}, or
the path of a statics JSON file. p0: initial guess [x, y] (m). solver: "auto" (Newton,
SOCP fallback), "socp" or "newton".
Returns the CLI's keys: p (m, ndarray), lengths (m), tensions (N), energy (J),
iterations, solve_us (us), residual, solver, converged.)doc");
  m.def("wrap", &wrapCall, "A"_a, "B"_a, "polygon"_a, "side"_a = "left",
        R"doc(wrap(A, B, polygon, side="left") -> dict

The taut cable path from A to B round a convex polygon (m), as `cablelab wrap`.
side "left": the cable passes on the left of the polygon walking from A to B.
Returns path ((k, 2) array, m), length (m) and contact_vertices (polygon indices in path
order).)doc");
  m.def("fit", &fitCall, "data"_a, "pulleys"_a, "sigma_fy"_a = py::none(),
        "sigma_angle_deg"_a = py::none(),
        R"doc(fit(data, pulleys, sigma_fy=None, sigma_angle_deg=None) -> dict

Fits the chapter 3 membrane model (stiffness k, preload) to force measurements, as
`cablelab fit`. data: a CSV path (header x,y,fy,angle_deg) or an (n, 4) array of x, y (m),
fy (N), angle_deg (degrees). pulleys: AX, AY, BX, BY (m). sigma_*: noise levels (N,
degrees), estimated when None. Returns the CLI's keys (k N/m, preload m, rms_fy N,
rms_angle_deg, k_stderr, preload_stderr, ...) plus covariance (2 x 2 of k, preload).)doc");
  m.def("membrane_data", &membraneDataCall, "k"_a, "preload"_a, "pulleys"_a, py::kw_only(),
        "noise_fy"_a = 0.05, "noise_angle_deg"_a = 1.0, "seed"_a = 1,
        "grid"_a = py::make_tuple(16, 12), "depth"_a = py::make_tuple(0.05, 0.35),
        "along"_a = py::make_tuple(0.1, 0.9),
        R"doc(membrane_data(k, preload, pulleys, *, noise_fy=0.05, noise_angle_deg=1, seed=1,
              grid=(16, 12), depth=(0.05, 0.35), along=(0.1, 0.9)) -> ndarray (n, 4)

Synthetic measurements x, y (m), fy (N), angle_deg from the membrane model with k (N/m)
and preload (m), as `cablelab fit --generate` (same seed, same numbers). grid: points along
the band x in depth; depth, along: fractions of |AB|.)doc");
  m.def("membrane_model", &membraneModelCall, "pulleys"_a, "k"_a, "preload"_a, "points"_a,
        R"doc(membrane_model(pulleys, k, preload, points) -> dict

The chapter 3 band between pulleys AX, AY, BX, BY (m) with stiffness k (N/m) and preload (m)
at contact points ((n, 2), m): force ((n, 2), N, the band's force on the point), tension
((n,), N) and angle_deg ((n,), direction of the force, degrees).)doc");
  m.def("scenes", &scenesCall,
        "scenes() -> list of {name, description, params: {NAME: {default, description}}}: the "
        "built-in scenes, as `cablelab scenes`.");
}

}  // namespace cablelab::python
