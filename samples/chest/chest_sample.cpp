// wirerig_chest_sample: the chest sample of issue 7 (paper Fig. 3, PHYSICS.md section 5).
//
// A clamped unit square plate (a = b = 1 m, D = 1 N m, q = 1 N/m^2) under a uniform load,
// solved by finite differences (plate_reference.h), against the 7-wire approximation of
// wire_patch.h: one closed-form clamped wire per profile and one xi per wire (Eq. 18). Prints
// the plate's centre deflection against the reference value, xi per wire, the errors of the
// wire model, and the time of a plate solve against one evaluation of the wires.
//
//   wirerig_chest_sample [--n N] [--repeat R] [--png OUT.png] [--exaggeration X]
//
// --n: plate grid intervals, a multiple of 12 (the Richardson check also solves n/2; default
// 96). --repeat: plate solves timed (default 5). --png: also draw the plate and the wire model
// side by side (needs the viewer). --exaggeration: deflection scale of the picture (default:
// the plate's peak drawn at about 25% of its width).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "plate_reference.h"
#include "wire_patch.h"

#ifdef WIRERIG_CHEST_HAS_VIEWER
#include "wirerig/viewer/camera.h"
#include "wirerig/viewer/headless.h"
#include "wirerig/viewer/render_frame.h"
#endif

namespace wirerig::chest {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kWires = 7;

struct Options {
  int intervals = 96;
  int repeat = 5;
  std::string png;
  double exaggeration = 0.0;  // 0: automatic
};

bool ParseOptions(int argc, char** argv, Options* options) {
  for (int k = 1; k < argc; ++k) {
    const std::string_view arg = argv[k];
    const bool has_value = k + 1 < argc;
    if (arg == "--n" && has_value) {
      options->intervals = std::atoi(argv[++k]);
    } else if (arg == "--repeat" && has_value) {
      options->repeat = std::atoi(argv[++k]);
    } else if (arg == "--png" && has_value) {
      options->png = argv[++k];
    } else if (arg == "--exaggeration" && has_value) {
      options->exaggeration = std::strtod(argv[++k], nullptr);
    } else {
      std::fprintf(stderr,
                   "usage: wirerig_chest_sample [--n N] [--repeat R] [--png OUT.png] "
                   "[--exaggeration X]\n  unknown or incomplete option: %s\n",
                   argv[k]);
      return false;
    }
  }
  if (options->intervals < 12 || options->intervals % 12 != 0 ||
      options->intervals > PlateProblem::kMaxIntervals) {
    std::fprintf(stderr, "--n: must be a multiple of 12 in [12, %d]\n",
                 PlateProblem::kMaxIntervals);
    return false;
  }
  if (options->repeat < 1 || options->repeat > 1000) {
    std::fprintf(stderr, "--repeat: must lie in [1, 1000]\n");
    return false;
  }
  if (!std::isfinite(options->exaggeration) || options->exaggeration < 0.0) {
    std::fprintf(stderr, "--exaggeration: must be a finite number >= 0\n");
    return false;
  }
  return true;
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

bool Check(const Status& status, const char* what) {
  if (status) return true;
  std::fprintf(stderr, "%s: %s\n", what, ToString(status).c_str());
  return false;
}

#ifdef WIRERIG_CHEST_HAS_VIEWER
// A triangulated (n + 1) x (n + 1) grid over the plate, x = u a - a/2, z = v b - b/2, drawn
// at y = -scale * deflection (the load pushes down).
struct GridMesh {
  std::vector<Vec3f> positions, normals;
  std::vector<Triangle> triangles;
  std::vector<float> scalars;
};

GridMesh MakeGridMesh(const PlateProblem& p, const std::vector<double>& deflection,
                      const std::vector<double>& scalars, double scale) {
  const int n = p.intervals;
  const std::uint32_t row = static_cast<std::uint32_t>(n + 1);
  GridMesh mesh;
  for (int i = 0; i <= n; ++i) {
    for (int k = 0; k <= n; ++k) {
      const std::size_t index = static_cast<std::size_t>(i) * row + static_cast<std::size_t>(k);
      mesh.positions.emplace_back(static_cast<float>(p.width * (double(i) / n - 0.5)),
                                  static_cast<float>(-scale * deflection[index]),
                                  static_cast<float>(p.length * (double(k) / n - 0.5)));
      mesh.scalars.push_back(static_cast<float>(scalars[index]));
    }
  }
  for (std::uint32_t i = 0; i < row - 1; ++i) {
    for (std::uint32_t k = 0; k < row - 1; ++k) {
      const std::uint32_t v00 = i * row + k, v10 = (i + 1) * row + k;
      const std::uint32_t v01 = v00 + 1, v11 = v10 + 1;
      // Counter-clockwise seen from +Y.
      mesh.triangles.push_back({v00, v01, v11});
      mesh.triangles.push_back({v00, v11, v10});
    }
  }
  mesh.normals.resize(mesh.positions.size());
  ComputeVertexNormals(mesh.positions, mesh.triangles, mesh.normals);
  return mesh;
}

// Two tiles: the plate (coloured by deflection) and the surface rebuilt from the 7 wires
// (coloured by its error), each with the wires drawn on top.
bool WritePicture(const Options& options, const PlateSolution& plate, const WirePatch& patch,
                  const std::vector<double>& wire_model) {
  const PlateProblem& p = plate.problem;
  const int n = p.intervals;
  const std::size_t count = static_cast<std::size_t>(n + 1);
  const int step = n / (kWires - 1);
  const double peak = plate.Peak();
  // Automatic: the peak drawn at about a quarter of the width, rounded to a multiple of 50.
  const double scale = options.exaggeration > 0.0
                           ? options.exaggeration
                           : std::max(1.0, 50.0 * std::round(0.25 * p.width / peak / 50.0));

  std::vector<double> surface(count * count), relative(count * count), error(count * count);
  double max_error = 0.0;
  for (int i = 0; i <= n; ++i) {
    const int left = std::min(i / step, kWires - 2);
    const double t = double(i - left * step) / step;
    for (int k = 0; k <= n; ++k) {
      const std::size_t index = static_cast<std::size_t>(i) * count + static_cast<std::size_t>(k);
      const double a = wire_model[static_cast<std::size_t>(left) * count + k];
      const double b = wire_model[static_cast<std::size_t>(left + 1) * count + k];
      surface[index] = (1.0 - t) * a + t * b;
      relative[index] = plate.deflection[index] / peak;
      error[index] = (surface[index] - plate.deflection[index]) / peak;
      max_error = std::max(max_error, std::abs(error[index]));
    }
  }
  GridMesh plate_mesh = MakeGridMesh(p, plate.deflection, relative, scale);
  GridMesh wire_mesh = MakeGridMesh(p, surface, error, scale);

  std::vector<std::vector<Vec3f>> wire_points(kWires);
  std::vector<RenderPolyline> polylines;
  for (int j = 0; j < kWires; ++j) {
    for (std::size_t k = 0; k < count; ++k) {
      wire_points[j].emplace_back(
          static_cast<float>(p.width * (patch.u[j] - 0.5)),
          static_cast<float>(-scale * wire_model[static_cast<std::size_t>(j) * count + k]),
          static_cast<float>(p.length * (double(k) / n - 0.5)));
    }
    RenderPolyline line;
    line.points = wire_points[j];
    line.kind = WireKind::kProfile;
    line.width = 4.0f;
    line.id = static_cast<std::uint32_t>(j);
    polylines.push_back(line);
  }

  RenderMesh plate_render;
  plate_render.positions = plate_mesh.positions;
  plate_render.normals = plate_mesh.normals;
  plate_render.triangles = plate_mesh.triangles;
  plate_render.scalars = plate_mesh.scalars;
  RenderMesh wire_render = plate_render;
  wire_render.positions = wire_mesh.positions;
  wire_render.normals = wire_mesh.normals;
  wire_render.scalars = wire_mesh.scalars;

  char plate_label[128], wire_label[128];
  std::snprintf(plate_label, sizeof(plate_label),
                "FD plate D lap^2 S = q, n = %d; deflection x%.0f (exaggerated)", n, scale);
  std::snprintf(wire_label, sizeof(wire_label),
                "7 wires, xi per wire (Eq. 18), linear across u; x%.0f (exaggerated)", scale);
  const float error_range =
      static_cast<float>(std::max(0.01, std::ceil(max_error * 100.0) / 100.0));

  std::vector<ContactSheetTile> tiles(2);
  tiles[0].frame.meshes = {&plate_render, 1};
  tiles[0].frame.polylines = polylines;
  tiles[0].frame.legend = {0.0f, 1.0f, ColorMap::kViridis, "plate deflection / peak", true};
  tiles[0].label = plate_label;
  tiles[1].frame.meshes = {&wire_render, 1};
  tiles[1].frame.polylines = polylines;
  tiles[1].frame.legend = {-error_range, error_range, ColorMap::kCoolWarm,
                           "(wire model - plate) / plate peak", true};
  tiles[1].label = wire_label;
  const Size tile_size{960, 720};
  for (ContactSheetTile& tile : tiles) {
    tile.camera.yaw = 0.55f;
    tile.camera.pitch = 0.45f;
    FrameCamera(tile.camera, ComputeFrameBounds(tile.frame), tile_size.Aspect(), 1.05f);
  }
  auto written = RenderContactSheet(tiles, tile_size, 2, options.png);
  if (!written) {
    std::fprintf(stderr, "--png: %s\n", written.error().c_str());
    return false;
  }
  std::printf("\npicture: %s (deflection x%.0f, exaggerated)\n", written.value().c_str(), scale);
  return true;
}
#endif

int Run(const Options& options) {
  const int n = options.intervals;
  PlateProblem problem;  // unit square, D = q = 1: deflections are in units of q a^4 / D
  problem.intervals = n;
  PlateProblem coarse_problem = problem;
  coarse_problem.intervals = n / 2;

  PlateSolution plate, coarse;
  std::vector<double> solve_seconds;
  for (int r = 0; r < options.repeat; ++r) {
    const Clock::time_point start = Clock::now();
    if (!Check(SolveClampedPlate(problem, &plate), "plate")) return 1;
    solve_seconds.push_back(Seconds(Clock::now() - start));
  }
  if (!Check(SolveClampedPlate(coarse_problem, &coarse), "coarse plate")) return 1;

  const double reference = kClampedSquareCentre;
  const double richardson = RichardsonH2(coarse.Centre(), plate.Centre());
  std::printf(
      "Chest sample (paper Fig. 3): clamped unit square plate, uniform q, D = q = a = 1\n\n");
  std::printf("Plate centre deflection, w_c D/(q a^4)      value       vs 0.00126532\n");
  auto centre_row = [reference](const std::string& name, double value) {
    std::printf("  %-40s %.8f   %+.4f%%\n", name.c_str(), value, 100.0 * (value / reference - 1.0));
  };
  centre_row("FD n = " + std::to_string(n / 2), coarse.Centre());
  centre_row("FD n = " + std::to_string(n), plate.Centre());
  centre_row("Richardson " + std::to_string(n / 2) + "/" + std::to_string(n), richardson);

  struct Row {
    const char* name;
    XiFit fit;
    WirePatch patch;
    WirePatchErrors errors;
  };
  Row rows[] = {{"no xi (xi = 1)", XiFit::kNone, {}, {}},
                {"single xi", XiFit::kSingle, {}, {}},
                {"xi per wire (Eq. 18)", XiFit::kPerWire, {}, {}}};
  for (Row& row : rows) {
    if (!Check(FitWirePatch(plate, kWires, row.fit, &row.patch), "fit")) return 1;
    if (!Check(CompareWithPlate(row.patch, plate, &row.errors), "compare")) return 1;
  }
  const Row& best = rows[2];
  WirePatch coarse_patch;
  if (!Check(FitWirePatch(coarse, kWires, XiFit::kPerWire, &coarse_patch), "fit")) return 1;

  std::printf("\n7 wires at u_j = j/6 (wires 0 and 6 on the clamped edges), n = %d\n", n);
  std::printf("  wire j                 1        2        3        4        5\n");
  std::printf("  xi_j (Eq. 18)   ");
  for (int j = 1; j < kWires - 1; ++j) std::printf("  %.4f", best.patch.xi[j]);
  std::printf("\n  xi_j Richardson ");
  for (int j = 1; j < kWires - 1; ++j)
    std::printf("  %.4f", RichardsonH2(coarse_patch.xi[j], best.patch.xi[j]));
  std::printf("   (%d/%d; PHYSICS.md: 0.1729 0.4053 0.4974)", n / 2, n);
  std::printf("\n  max err / peak  ");
  for (int j = 1; j < kWires - 1; ++j) std::printf("  %.4f", best.errors.max_per_wire[j]);
  std::printf("\n\nErrors relative to the plate peak (%.8f)\n", best.errors.plate_peak);
  std::printf("  %-22s %8s %10s %10s %12s %12s\n", "wire model", "xi", "max wires", "RMS wires",
              "max surface", "RMS surface");
  for (const Row& row : rows) {
    char xi[16] = "per wire";
    if (row.fit != XiFit::kPerWire) std::snprintf(xi, sizeof(xi), "%.4f", row.patch.xi[1]);
    std::printf("  %-22s %8s %10.4f %10.4f %12.4f %12.4f\n", row.name, xi, row.errors.max_on_wires,
                row.errors.rms_on_wires, row.errors.max_surface, row.errors.rms_surface);
  }

  // Timing: the wires at the plate's n + 1 nodes, xi precomputed (the fit needs one plate solve).
  const std::size_t count = static_cast<std::size_t>(n + 1);
  std::vector<double> samples(count);
  for (std::size_t k = 0; k < count; ++k) samples[k] = double(k) / n;
  std::vector<Vec3> scratch(count);
  std::vector<double> wire_model(kWires * count);
  WirePatchJob job;
  job.patch = &best.patch;
  job.pressure = problem.pressure;
  job.samples = samples;
  job.scratch = scratch;
  job.deflection = wire_model;
  constexpr int kBatch = 200;
  std::vector<double> wire_seconds;
  const Clock::time_point timing_start = Clock::now();
  while (wire_seconds.size() < 25 || Seconds(Clock::now() - timing_start) < 0.2) {
    const Clock::time_point start = Clock::now();
    for (int r = 0; r < kBatch; ++r) {
      if (!Check(job.Run(), "wires")) return 1;
    }
    wire_seconds.push_back(Seconds(Clock::now() - start) / kBatch);
  }
  const double plate_time = Median(solve_seconds);
  const double wire_time = Median(wire_seconds);
  std::printf("\nTiming (median; one thread; 5 wires at %zu samples each, xi precomputed)\n",
              count);
  std::printf("  plate solve, n = %-4d (assembly + LDLT)  %10.3e s\n", n, plate_time);
  std::printf("  wire evaluation (5 BendingJobs)           %10.3e s\n", wire_time);
  if (wire_time > 0.0)
    std::printf("  ratio plate / wires                       %10.3e\n", plate_time / wire_time);

#ifdef WIRERIG_CHEST_HAS_VIEWER
  if (!options.png.empty() && !WritePicture(options, plate, best.patch, wire_model)) return 1;
#else
  if (!options.png.empty()) {
    std::fprintf(stderr, "--png: this build has no viewer (WIRERIG_BUILD_VIEWER=OFF)\n");
    return 1;
  }
#endif
  return 0;
}

}  // namespace
}  // namespace wirerig::chest

int main(int argc, char** argv) {
  wirerig::chest::Options options;
  if (!wirerig::chest::ParseOptions(argc, argv, &options)) return 2;
  return wirerig::chest::Run(options);
}
