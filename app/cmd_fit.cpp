// `cablelab fit`: fits the chapter 3 membrane model (stiffness k, preload) to force
// measurements, or with --generate writes a synthetic data set from known parameters.
//
//   cablelab fit DATA.csv --pulleys AX,AY,BX,BY [--plots DIR] [--sigma-fy N] [--sigma-angle-deg D]
//   cablelab fit --generate OUT.csv --pulleys AX,AY,BX,BY --k K --preload P
//                [--noise-fy N] [--noise-angle-deg D] [--seed S] [--grid NXxNY]
//                [--depth MIN,MAX] [--along MIN,MAX]
#include <algorithm>
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
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "engine/membrane/membrane_data.h"
#include "engine/membrane/membrane_fit.h"
#include "engine/membrane/membrane_fit_io.h"
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

double parseDouble(const std::string& text, const std::string& flag) {
  return parseNumber(text, kCommandLine, flag);
}

MembraneGeometry parsePulleys(const std::string& text) {
  if (text.empty())
    throw InputError(kCommandLine, "--pulleys",
                     "is required: --pulleys AX,AY,BX,BY (m) (got nothing)");
  return membranePulleys(parseNumberList(text, 4, kCommandLine, "--pulleys", "AX,AY,BX,BY"));
}

int runGenerate(const FitOptions& o) {
  if (!o.data.empty())
    throw InputError(
        kCommandLine, "DATA",
        "give either DATA.csv (fit) or --generate OUT.csv, not both" + gotValue(o.data));
  MembraneSynthDef def;
  def.geometry = parsePulleys(o.pulleys);
  if (o.k.empty())
    throw InputError(kCommandLine, "--k", "is required with --generate (N/m) (got nothing)");
  if (o.preload.empty())
    throw InputError(kCommandLine, "--preload", "is required with --generate (m) (got nothing)");
  def.params.k = parseDouble(o.k, "--k");
  def.params.preload = parseDouble(o.preload, "--preload");
  def.noiseFy = parseDouble(o.noiseFy, "--noise-fy");
  def.noiseAngleDeg = parseDouble(o.noiseAngleDeg, "--noise-angle-deg");
  def.seed = static_cast<std::uint64_t>(
      parseWholeNumber(o.seed, kCommandLine, "--seed", 0, 9007199254740992L));
  const PixelSize grid = parsePixelSize(o.grid, kCommandLine, "--grid", 1, 1000000);
  def.nx = grid.width;
  def.ny = grid.height;
  const auto depth = parseNumberList(o.depth, 2, kCommandLine, "--depth", "MIN,MAX");
  const auto along = parseNumberList(o.along, 2, kCommandLine, "--along", "MIN,MAX");
  def.depthMin = depth[0];
  def.depthMax = depth[1];
  def.alongMin = along[0];
  def.alongMax = along[1];
  try {
    validateMembraneSynth(def, kCommandLine);
  } catch (const InputError& e) {  // name the option the field came from
    std::string option = "--" + e.field();
    std::replace(option.begin(), option.end(), '_', '-');
    throw InputError(kCommandLine, option, e.detail());
  }

  const auto rows = generateMembraneData(def);
  {
    std::ofstream out = openOutputFile(o.generate, "--generate");
    writeMembraneCsv(out, rows);
    finishOutputFile(out, o.generate, "--generate");
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

int runFit(const FitOptions& o) {
  if (o.data.empty())
    throw InputError(kCommandLine, "DATA",
                     "is required: cablelab fit DATA.csv --pulleys ... (or --generate OUT.csv) "
                     "(got nothing)");
  for (const auto& [value, flag] : {std::pair{o.k, "--k"}, std::pair{o.preload, "--preload"}})
    if (!value.empty())
      throw InputError(kCommandLine, flag, "only with --generate" + gotValue(value));
  const MembraneGeometry g = parsePulleys(o.pulleys);
  MembraneFitOptions options;
  options.source = o.data;
  if (!o.sigmaFy.empty())
    options.sigmaFy = membraneSigma(parseDouble(o.sigmaFy, "--sigma-fy"), "--sigma-fy");
  if (!o.sigmaAngleDeg.empty())
    options.sigmaAngleDeg =
        membraneSigma(parseDouble(o.sigmaAngleDeg, "--sigma-angle-deg"), "--sigma-angle-deg");

  const auto rows = loadMembraneCsv(o.data, g);
  const auto start = std::chrono::steady_clock::now();
  const MembraneFitResult fit = fitMembrane(g, rows, options);
  const double fitUs =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();

  nlohmann::ordered_json j = membraneFitJson(fit, options, fitUs);

  if (!o.plots.empty()) {
    const auto [width, height] = parsePixelSize(o.plotSize, kCommandLine, "--plot-size", 200, 4096);
    const std::filesystem::path dir(o.plots);
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error)
      throw InputError(kCommandLine, "--plots",
                       "cannot create the folder: " + error.message() + gotValue(o.plots));
    const MembranePlotData plot = makeMembranePlotData(g, fit.params, rows);
    const std::string quiverCsv = (dir / "quiver.csv").string();
    const std::string scatterCsv = (dir / "scatter.csv").string();
    std::ofstream quiver = openOutputFile(quiverCsv, "--plots");
    writeQuiverCsv(quiver, plot);
    finishOutputFile(quiver, quiverCsv, "--plots");
    std::ofstream scatter = openOutputFile(scatterCsv, "--plots");
    writeScatterCsv(scatter, plot);
    finishOutputFile(scatter, scatterCsv, "--plots");
    j["plots"] = {(dir / "quiver.csv").string(), (dir / "scatter.csv").string()};
#ifdef CABLELAB_HAVE_OFFSCREEN
    try {
      ui::writeMembraneFigures(g, fit.params, plot, dir.string(), width, height);
    } catch (const std::exception& e) {
      throw InputError(kCommandLine, "--plots", e.what());
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

static const bool fitRegistered = registerCommand(
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
