// Open CASCADE's GeomAPI_PointsToBSpline, the nearest Open CASCADE call to lekalo's tolerance
// fit, timed in C++ for bench/peers/fit_peers.py (the 10^5 points of a plane spiral of
// crates/lekalo/benches/fit.rs, written by lekalo's example fit_peer) and
// bench/python/tolerance_bench.py (a helix of up to 2·10^6 points): degree 3 to DEGMAX, C2, the
// tolerance given. Prints one JSON line: the median wall time and the CPU time of the repeats,
// the control-point count and degree, and the largest distance from the points to the curve
// (GeomAPI_ProjectPointOnCurve, at most 100,000 points evenly spread, so that it compares with
// lekalo's max_deviation).
//
// Usage: occt_fit POINTS.bin DIM [REPEATS] [TOL] [DEGMAX]
// POINTS.bin: the points as little-endian float64, DIM (2 or 3) numbers a point.
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <GeomAbs_Shape.hxx>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

// CPU time of the process, all threads, in seconds.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: occt_fit POINTS.bin DIM [REPEATS] [TOL] [DEGMAX]\n");
    return 2;
  }
  const int dim = std::atoi(argv[2]);
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 3;
  const double tol = argc > 4 ? std::atof(argv[4]) : 1e-3;
  const int degmax = argc > 5 ? std::atoi(argv[5]) : 3;
  std::ifstream f(argv[1], std::ios::binary);
  if (!f || (dim != 2 && dim != 3)) {
    std::fprintf(stderr, "occt_fit: cannot read %s as points of dimension %d\n", argv[1], dim);
    return 2;
  }
  f.seekg(0, std::ios::end);
  const size_t bytes = f.tellg();
  f.seekg(0);
  std::vector<double> xs(bytes / sizeof(double));
  f.read(reinterpret_cast<char*>(xs.data()), static_cast<std::streamsize>(xs.size() * sizeof(double)));
  const int n = static_cast<int>(xs.size() / dim);
  TColgp_Array1OfPnt pts(1, n);
  for (int i = 0; i < n; ++i) {
    pts.SetValue(i + 1, gp_Pnt(xs[dim * i], xs[dim * i + 1], dim == 3 ? xs[dim * i + 2] : 0.0));
  }

  std::vector<double> times;
  const double cpu0 = cpu_seconds();
  Handle(Geom_BSplineCurve) curve;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    auto t0 = std::chrono::steady_clock::now();
    GeomAPI_PointsToBSpline fit(pts, 3, degmax, GeomAbs_C2, tol);
    if (!fit.IsDone()) {
      std::fprintf(stderr, "occt_fit: GeomAPI_PointsToBSpline failed\n");
      return 3;
    }
    curve = fit.Curve();
    auto t1 = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double>(t1 - t0).count());
  }
  const double cpu = (cpu_seconds() - cpu0) / static_cast<double>(times.size());
  std::sort(times.begin(), times.end());
  const double secs = times[times.size() / 2];
  double maxdev = 0.0;
  GeomAPI_ProjectPointOnCurve proj;
  const int step = std::max(1, n / 100000);
  for (int i = 1; i <= n; i += step) {
    proj.Init(pts.Value(i), curve);
    if (proj.NbPoints() > 0) maxdev = std::max(maxdev, proj.LowerDistance());
  }
  std::printf(
      "{\"secs\": %.6g, \"cpu\": %.6g, \"n_ctrl\": %d, \"degree\": %d, \"tol\": %g, "
      "\"max_deviation\": %.6g}\n",
      secs, cpu, curve->NbPoles(), curve->Degree(), tol, maxdev);
  return 0;
}
