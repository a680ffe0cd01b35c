// The tolerance fit of crates/lekalo/benches/fit.rs against Open CASCADE's
// GeomAPI_PointsToBSpline: the same 10^5 points of a plane spiral (DIR/tol_q.bin, written by
// lekalo's example fit_peer), the same tolerance and degree. Prints one JSON line: median time,
// control-point count, and the largest distance from the points to OCCT's curve (measured with
// GeomAPI_ProjectPointOnCurve from the approximation's own parameters, so it can be compared
// with lekalo's max_deviation).
//
// Usage: occt_fit DIR [REPEATS] [TOL]   (built by bench/peers/run.sh or fit_peers.py)
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <GeomAbs_Shape.hxx>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: occt_fit DIR [REPEATS] [TOL]\n");
    return 2;
  }
  std::string dir = argv[1];
  int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  double tol = argc > 3 ? std::atof(argv[3]) : 1e-3;
  std::ifstream f(dir + "/tol_q.bin", std::ios::binary);
  if (!f) {
    std::fprintf(stderr, "occt_fit: no %s/tol_q.bin (run lekalo's example fit_peer first)\n",
                 dir.c_str());
    return 2;
  }
  f.seekg(0, std::ios::end);
  size_t bytes = f.tellg();
  f.seekg(0);
  std::vector<double> xy(bytes / sizeof(double));
  f.read(reinterpret_cast<char*>(xy.data()), bytes);
  int n = static_cast<int>(xy.size() / 2);
  TColgp_Array1OfPnt pts(1, n);
  for (int i = 0; i < n; ++i) pts.SetValue(i + 1, gp_Pnt(xy[2 * i], xy[2 * i + 1], 0.0));

  std::vector<double> times;
  Handle(Geom_BSplineCurve) curve;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    auto t0 = std::chrono::steady_clock::now();
    GeomAPI_PointsToBSpline fit(pts, 3, 3, GeomAbs_C2, tol);
    if (!fit.IsDone()) {
      std::fprintf(stderr, "occt_fit: GeomAPI_PointsToBSpline failed\n");
      return 3;
    }
    curve = fit.Curve();
    auto t1 = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double>(t1 - t0).count());
  }
  std::sort(times.begin(), times.end());
  double secs = times[times.size() / 2];
  double maxdev = 0.0;
  GeomAPI_ProjectPointOnCurve proj;
  for (int i = 1; i <= n; ++i) {
    proj.Init(pts.Value(i), curve);
    if (proj.NbPoints() > 0) maxdev = std::max(maxdev, proj.LowerDistance());
  }
  std::printf("{\"secs\": %.6g, \"n_ctrl\": %d, \"degree\": %d, \"tol\": %g, \"max_deviation\": %.6g}\n",
              secs, curve->NbPoles(), curve->Degree(), tol, maxdev);
  return 0;
}
