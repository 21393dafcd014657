// `cablelab fit`: fits the chapter 3 membrane model (stiffness k, preload) to force
// measurements, or with --generate writes a synthetic data set from known parameters.
//
//   cablelab fit DATA.csv --pulleys AX,AY,BX,BY [--plots DIR] [--sigma-fy N] [--sigma-angle-deg D]
//   cablelab fit --generate OUT.csv --pulleys AX,AY,BX,BY --k K --preload P
//                [--noise-fy N] [--noise-angle-deg D] [--seed S] [--grid NXxNY]
//                [--depth MIN,MAX] [--along MIN,MAX]
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/command.h"
#include "engine/core/error.h"
#include "engine/membrane/membrane_data.h"
#include "engine/membrane/membrane_fit.h"
#include "engine/membrane/membrane_plot.h"
#include "engine/membrane/membrane_synth.h"
#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/membrane_figures.h"
#endif

namespace cablelab::app {
namespace {

struct FitOptions {
  std::string data;
  std::string pulleys;
  std::string plots;
  std::string plotSize = "800x600";
  std::string sigmaFy;
  std::string sigmaAngleDeg;
  // --generate mode
  std::string generate;
  std::string k;
  std::string preload;
  std::string noiseFy = "0.05";
  std::string noiseAngleDeg = "1";
  std::string seed = "1";
  std::string grid = "16x12";
  std::string depth = "0.05,0.35";
  std::string along = "0.1,0.9";
};

double parseDouble(const std::string& text, const std::string& flag, const std::string& field) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || stop != end || !std::isfinite(value))
    throw InputError(flag, field, "expected a finite number (got \"" + text + "\")");
  return value;
}

/// "a,b,c" -> exactly `count` finite numbers.
std::vector<double> parseList(const std::string& text, size_t count, const std::string& flag,
                              const std::string& field, const std::string& shape) {
  std::vector<double> values;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? comma : comma - start);
    values.push_back(parseDouble(item, flag, field));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != count)
    throw InputError(flag, field,
                     "expected " + shape + " (" + std::to_string(count) + " numbers, got " +
                         std::to_string(values.size()) + ")");
  return values;
}

MembraneGeometry parsePulleys(const std::string& text) {
  if (text.empty()) throw InputError("--pulleys", "pulleys", "required: --pulleys AX,AY,BX,BY (m)");
  const auto v = parseList(text, 4, "--pulleys", "pulleys", "AX,AY,BX,BY");
  MembraneGeometry g{Vec2(v[0], v[1]), Vec2(v[2], v[3])};
  validateMembraneGeometry(g, "--pulleys");
  return g;
}

std::ofstream openForWriting(const std::filesystem::path& path, const std::string& flag) {
  std::ofstream out(path);
  if (!out) throw InputError(path.string(), flag, "cannot open for writing");
  return out;
}

int runGenerate(const FitOptions& o) {
  if (!o.data.empty())
    throw InputError(o.data, "DATA", "give either DATA.csv (fit) or --generate OUT.csv, not both");
  MembraneSynthDef def;
  def.geometry = parsePulleys(o.pulleys);
  if (o.k.empty()) throw InputError("--k", "k", "required with --generate (N/m)");
  if (o.preload.empty()) throw InputError("--preload", "preload", "required with --generate (m)");
  def.params.k = parseDouble(o.k, "--k", "k");
  def.params.preload = parseDouble(o.preload, "--preload", "preload");
  def.noiseFy = parseDouble(o.noiseFy, "--noise-fy", "noise_fy");
  def.noiseAngleDeg = parseDouble(o.noiseAngleDeg, "--noise-angle-deg", "noise_angle_deg");
  const double seed = parseDouble(o.seed, "--seed", "seed");
  if (seed < 0 || seed != std::floor(seed) || seed > 9.007199254740992e15)
    throw InputError("--seed", "seed", "must be a whole number >= 0");
  def.seed = static_cast<std::uint64_t>(seed);
  const size_t x = o.grid.find_first_of("xX");
  if (x == std::string::npos) throw InputError("--grid", "grid", "expected NXxNY, e.g. 16x12");
  const double nx = parseDouble(o.grid.substr(0, x), "--grid", "grid");
  const double ny = parseDouble(o.grid.substr(x + 1), "--grid", "grid");
  if (nx != std::floor(nx) || ny != std::floor(ny) || nx < 1 || ny < 1 || nx * ny > 1e6)
    throw InputError("--grid", "grid", "NX and NY must be whole numbers >= 1, at most 1e6 points");
  def.nx = static_cast<int>(nx);
  def.ny = static_cast<int>(ny);
  const auto depth = parseList(o.depth, 2, "--depth", "depth", "MIN,MAX");
  const auto along = parseList(o.along, 2, "--along", "along", "MIN,MAX");
  def.depthMin = depth[0];
  def.depthMax = depth[1];
  def.alongMin = along[0];
  def.alongMax = along[1];
  validateMembraneSynth(def, "--generate");

  const auto rows = generateMembraneData(def);
  {
    std::ofstream out = openForWriting(o.generate, "--generate");
    writeMembraneCsv(out, rows);
    if (!out.flush()) throw InputError(o.generate, "--generate", "write failed");
  }
  // The generating parameters, with units: save this next to the CSV to document it.
  nlohmann::ordered_json j;
  j["generated"] = o.generate;
  j["rows"] = rows.size();
  j["k"] = def.params.k;
  j["preload"] = def.params.preload;
  j["pulleys"] = {def.geometry.a.x(), def.geometry.a.y(), def.geometry.b.x(), def.geometry.b.y()};
  j["noise_fy"] = def.noiseFy;
  j["noise_angle_deg"] = def.noiseAngleDeg;
  j["seed"] = def.seed;
  j["grid"] = {def.nx, def.ny};
  j["depth"] = {def.depthMin, def.depthMax};
  j["along"] = {def.alongMin, def.alongMax};
  j["units"] = {{"k", "N/m"},
                {"preload", "m"},
                {"pulleys", "m, AX,AY,BX,BY"},
                {"noise_fy", "N, standard deviation"},
                {"noise_angle_deg", "degrees, standard deviation"},
                {"grid", "points along the band x points in depth"},
                {"depth", "fraction of |AB|, right of A->B (below for A left of B)"},
                {"along", "fraction of |AB| from A"}};
  printJson(j.dump());
  return 0;
}

/// "WxH" -> pixel sizes, each in [200, 4096].
std::pair<int, int> parsePlotSize(const std::string& text) {
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos)
    throw InputError("--plot-size", "plot_size", "expected WxH, e.g. 800x600");
  const double w = parseDouble(text.substr(0, x), "--plot-size", "plot_size");
  const double h = parseDouble(text.substr(x + 1), "--plot-size", "plot_size");
  if (w != std::floor(w) || h != std::floor(h) || w < 200 || h < 200 || w > 4096 || h > 4096)
    throw InputError("--plot-size", "plot_size", "W and H must be whole numbers in 200..4096 (px)");
  return {static_cast<int>(w), static_cast<int>(h)};
}

int runFit(const FitOptions& o) {
  if (o.data.empty())
    throw InputError("fit", "DATA",
                     "required: cablelab fit DATA.csv --pulleys ... (or --generate OUT.csv)");
  for (const auto& [value, flag] : {std::pair{o.k, "--k"}, std::pair{o.preload, "--preload"}})
    if (!value.empty()) throw InputError(flag, "generate", "only with --generate");
  const MembraneGeometry g = parsePulleys(o.pulleys);
  MembraneFitOptions options;
  options.source = o.data;
  if (!o.sigmaFy.empty()) {
    options.sigmaFy = parseDouble(o.sigmaFy, "--sigma-fy", "sigma_fy");
    if (options.sigmaFy <= 0) throw InputError("--sigma-fy", "sigma_fy", "must be positive (N)");
  }
  if (!o.sigmaAngleDeg.empty()) {
    options.sigmaAngleDeg = parseDouble(o.sigmaAngleDeg, "--sigma-angle-deg", "sigma_angle_deg");
    if (options.sigmaAngleDeg <= 0)
      throw InputError("--sigma-angle-deg", "sigma_angle_deg", "must be positive (degrees)");
  }

  const auto rows = loadMembraneCsv(o.data, g);
  const auto start = std::chrono::steady_clock::now();
  const MembraneFitResult fit = fitMembrane(g, rows, options);
  const double fitUs =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();

  nlohmann::ordered_json j;
  j["k"] = fit.params.k;
  j["preload"] = fit.params.preload;
  j["rms_fy"] = fit.rmsFy;
  j["rms_angle_deg"] = fit.rmsAngleDeg;
  j["k_stderr"] = fit.kStderr;
  j["preload_stderr"] = fit.preloadStderr;
  j["k_preload_correlation"] =
      fit.covariance(0, 1) / std::sqrt(fit.covariance(0, 0) * fit.covariance(1, 1));
  j["sigma_fy"] = fit.sigmaFy;
  j["sigma_angle_deg"] = fit.sigmaAngleDeg;
  j["sigmas"] = (options.sigmaFy > 0 && options.sigmaAngleDeg > 0)   ? "given"
                : (options.sigmaFy > 0 || options.sigmaAngleDeg > 0) ? "partly estimated"
                                                                     : "estimated";
  j["chi2_per_dof"] = fit.chi2PerDof;
  j["iterations"] = fit.iterations;
  j["rounds"] = fit.rounds;
  j["rows"] = fit.rows;
  j["fit_us"] = fitUs;

  if (!o.plots.empty()) {
    const auto [width, height] = parsePlotSize(o.plotSize);
    const std::filesystem::path dir(o.plots);
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw InputError(o.plots, "--plots", "cannot create directory: " + error.message());
    const MembranePlotData plot = makeMembranePlotData(g, fit.params, rows);
    std::ofstream quiver = openForWriting(dir / "quiver.csv", "--plots");
    writeQuiverCsv(quiver, plot);
    std::ofstream scatter = openForWriting(dir / "scatter.csv", "--plots");
    writeScatterCsv(scatter, plot);
    if (!quiver.flush() || !scatter.flush()) throw InputError(o.plots, "--plots", "write failed");
    j["plots"] = {(dir / "quiver.csv").string(), (dir / "scatter.csv").string()};
#ifdef CABLELAB_HAVE_OFFSCREEN
    try {
      ui::writeMembraneFigures(g, fit.params, plot, dir.string(), width, height);
    } catch (const std::exception& e) {
      throw InputError(o.plots, "--plots", e.what());
    }
    j["plots"].push_back((dir / "quiver.png").string());
    j["plots"].push_back((dir / "scatter.png").string());
#else
    (void)width, (void)height;
    j["plots_note"] = "this build has no offscreen renderer: CSV only, no PNG";
#endif
  }
  printJson(j.dump());
  return 0;
}

}  // namespace

static const bool registered = registerCommand(
    "fit", "Fit membrane stiffness k and preload to force data (thesis ch. 3), or --generate data",
    [](CLI::App& sub) -> std::function<int()> {
      auto o = std::make_shared<FitOptions>();
      sub.add_option("DATA", o->data,
                     "CSV with header x,y,fy,angle_deg: contact point (m), measured vertical "
                     "force (N), measured force direction atan2(Fy,Fx) (degrees)");
      sub.add_option("--pulleys", o->pulleys, "pulley positions AX,AY,BX,BY (m)");
      sub.add_option("--plots", o->plots,
                     "directory for the chapter 3 figures: quiver.png and scatter.png (figures 3-2 "
                     "and 3-3) and their data, quiver.csv and scatter.csv");
      sub.add_option("--plot-size", o->plotSize, "size of each plot PNG, WxH (px)")
          ->capture_default_str();
      sub.add_option("--sigma-fy", o->sigmaFy, "noise level of fy (N); default: estimated");
      sub.add_option("--sigma-angle-deg", o->sigmaAngleDeg,
                     "noise level of angle_deg (degrees); default: estimated");
      sub.add_option(
          "--generate", o->generate,
          "write a synthetic data set OUT.csv instead of fitting (needs --k, --preload)");
      sub.add_option("--k", o->k, "generate: band stiffness (N/m)");
      sub.add_option("--preload", o->preload, "generate: preload stretch (m), >= 0");
      sub.add_option("--noise-fy", o->noiseFy, "generate: fy noise standard deviation (N)")
          ->capture_default_str();
      sub.add_option("--noise-angle-deg", o->noiseAngleDeg,
                     "generate: angle noise standard deviation (degrees)")
          ->capture_default_str();
      sub.add_option("--seed", o->seed, "generate: noise seed (whole number)")
          ->capture_default_str();
      sub.add_option("--grid", o->grid, "generate: NXxNY points along the band x in depth")
          ->capture_default_str();
      sub.add_option("--depth", o->depth,
                     "generate: MIN,MAX depth as fractions of |AB|, positive = right of A->B "
                     "(below for A left of B)")
          ->capture_default_str();
      sub.add_option("--along", o->along, "generate: MIN,MAX position along AB as fractions from A")
          ->capture_default_str();
      return [o] { return o->generate.empty() ? runFit(*o) : runGenerate(*o); };
    });

}  // namespace cablelab::app
