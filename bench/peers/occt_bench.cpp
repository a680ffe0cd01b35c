// Open CASCADE Technology timed in C++ on the workload files of `examples/peer_bench.rs`, so
// that the peer comparison measures its geometry kernel and not a Python binding's per-call
// cost. Built and run by bench/peers/run.sh (through peers.py) when Debian's
// libocct-modeling-algorithms-dev (or another OCCT install with headers) is present.
//
// Usage: occt_bench DATA_DIR REPEATS N_CTRL N INTERP_SIZES SURFACE_SIZES ELEVATIONS
//   INTERP_SIZES and SURFACE_SIZES as comma lists (1000,10000), ELEVATIONS as a,b pairs joined
//   by ';' (10,20;50,100); the evaluation curve is a cubic in 3-D, as peer_bench writes it, and
//   N = 0 leaves evaluation out (peers.py times one workload at a time; empty lists are fine).
// Prints one tab-separated line a measurement: workload, peer, ns per unit, note.
// Timing as peers.py's median_ns: one warm-up call that also sets how many calls make a sample
// of at least 20 ms, then the median of REPEATS samples.

#include <GeomAPI_Interpolate.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>
#include <gp_XYZ.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::string g_dir;
int g_repeats = 7;

std::vector<double> read_f64(const std::string& name) {
  std::ifstream f(g_dir + "/" + name, std::ios::binary | std::ios::ate);
  if (!f) throw std::runtime_error("cannot open " + g_dir + "/" + name);
  std::streamsize bytes = f.tellg();
  f.seekg(0);
  std::vector<double> v(static_cast<size_t>(bytes) / sizeof(double));
  f.read(reinterpret_cast<char*>(v.data()), bytes);  // little-endian, as on x86-64
  return v;
}

// median wall time of the samples, in ns per unit (see the header)
double median_ns(const std::function<void()>& fn, double units) {
  using clock = std::chrono::steady_clock;
  auto secs = [](clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  auto t0 = clock::now();
  fn();
  double once = secs(t0, clock::now());
  long inner = std::max(1L, static_cast<long>(std::ceil(0.02 / std::max(once, 1e-9))));
  std::vector<double> times;
  for (int r = 0; r < std::max(1, g_repeats); ++r) {
    t0 = clock::now();
    for (long i = 0; i < inner; ++i) fn();
    times.push_back(secs(t0, clock::now()) / inner);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2] * 1e9 / units;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

// largest |a_i - b_i| over the common length
double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) m = std::max(m, std::fabs(a[i] - b[i]));
  return m;
}

// Times `at(adaptor, t)` (a gp_XYZ: a point or a derivative) at every parameter of `ts` into
// `out` (3 numbers a parameter), with a fresh adaptor, so a fresh span cache, per batch; `out`
// holds the last batch on return. ns per parameter.
template <class At>
double time_batch(const Handle(Geom_BSplineCurve) & curve, const std::vector<double>& ts,
                  std::vector<double>& out, At at) {
  auto batch = [&]() {
    GeomAdaptor_Curve adaptor(curve);
    for (size_t i = 0; i < ts.size(); ++i) {
      gp_XYZ v = at(adaptor, ts[i]);
      out[3 * i] = v.X();
      out[3 * i + 1] = v.Y();
      out[3 * i + 2] = v.Z();
    }
  };
  double ns = median_ns(batch, static_cast<double>(ts.size()));
  batch();
  return ns;
}

void row(const std::string& work, const std::string& peer, double ns, const std::string& note) {
  std::printf("%s\t%s\t%.6g\t%s\n", work.c_str(), peer.c_str(), ns, note.c_str());
  std::fflush(stdout);
}

std::string sci(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1e", x);
  return b;
}

std::vector<long> parse_list(const std::string& s, char sep) {
  std::vector<long> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep))
    if (!item.empty()) v.push_back(std::stol(item));
  return v;
}

TColgp_Array1OfPnt poles_of(const std::vector<double>& xyz) {
  int n = static_cast<int>(xyz.size() / 3);
  TColgp_Array1OfPnt a(1, n);
  for (int i = 0; i < n; ++i) a.SetValue(i + 1, gp_Pnt(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
  return a;
}

// cubic 3-D B-spline at 10^6 sorted and random parameters: GeomAdaptor_Curve (its span cache)
void evaluation(int n_ctrl, long n) {
  std::vector<double> knots = read_f64("knots.bin"), ctrl = read_f64("ctrl.bin");
  std::vector<double> distinct;
  std::vector<int> mults;
  for (double k : knots) {
    if (!distinct.empty() && distinct.back() == k) {
      ++mults.back();
    } else {
      distinct.push_back(k);
      mults.push_back(1);
    }
  }
  TColStd_Array1OfReal kn(1, static_cast<int>(distinct.size()));
  TColStd_Array1OfInteger mu(1, static_cast<int>(distinct.size()));
  for (size_t i = 0; i < distinct.size(); ++i) {
    kn.SetValue(static_cast<int>(i) + 1, distinct[i]);
    mu.SetValue(static_cast<int>(i) + 1, mults[i]);
  }
  const int degree = static_cast<int>(knots.size()) - n_ctrl - 1;
  Handle(Geom_BSplineCurve) curve = new Geom_BSplineCurve(poles_of(ctrl), kn, mu, degree);
  const double scale = max_abs(ctrl);
  std::vector<double> out(3 * n);
  for (const char* order : {"sorted", "random"}) {
    std::vector<double> ts = read_f64(std::string("ts_") + order + ".bin");
    double ns = time_batch(curve, ts, out,
                           [](GeomAdaptor_Curve& a, double t) { return a.Value(t).XYZ(); });
    double diff = max_abs_diff(out, read_f64(std::string("ours_eval_") + order + ".bin"));
    row(std::string("eval_") + order, "OCCT C++ GeomAdaptor_Curve::Value", ns,
        "diff " + sci(diff / scale) + " rel");
  }
  double ns = time_batch(curve, read_f64("ts_sorted.bin"), out, [](GeomAdaptor_Curve& a, double t) {
    gp_Pnt p;
    gp_Vec d;
    a.D1(t, p, d);
    return d.XYZ();
  });
  std::vector<double> ours = read_f64("ours_deriv1_sorted.bin");
  row("deriv1_sorted", "OCCT C++ GeomAdaptor_Curve::D1", ns,
      "point and 1st derivative; diff " + sci(max_abs_diff(out, ours) / max_abs(ours)) + " rel");
}

// cubic interpolation through n 3-D points: GeomAPI_Interpolate, given our chord-length
// parameters, and with its own (cumulative chord lengths)
void interpolation(long n) {
  const std::string sn = std::to_string(n);
  std::vector<double> q = read_f64("interp_q_" + sn + ".bin"), t = read_f64("interp_t_" + sn + ".bin");
  const double scale = max_abs(q);
  const int ni = static_cast<int>(n);
  auto fill = [&]() {
    Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, ni);
    for (int i = 0; i < ni; ++i) pts->SetValue(i + 1, gp_Pnt(q[3 * i], q[3 * i + 1], q[3 * i + 2]));
    return pts;
  };
  auto fit_at_data = [&](const Handle(Geom_BSplineCurve)& c, const std::vector<double>& at) {
    double err = 0.0;
    long step = std::max(1L, n / 2000);
    for (long i = 0; i < n; i += step)
      err = std::max(err, c->Value(at[i]).Distance(gp_Pnt(q[3 * i], q[3 * i + 1], q[3 * i + 2])));
    return err / scale;
  };

  Handle(TColgp_HArray1OfPnt) pts = fill();
  Handle(TColStd_HArray1OfReal) par = new TColStd_HArray1OfReal(1, ni);
  for (int i = 0; i < ni; ++i) par->SetValue(i + 1, t[i]);
  Handle(Geom_BSplineCurve) curve;
  auto solve = [&]() {
    GeomAPI_Interpolate it(pts, par, Standard_False, 1e-12);
    it.Perform();
    curve = it.Curve();
  };
  double ns = median_ns(solve, static_cast<double>(n));
  row("interp_" + sn, "OCCT C++ GeomAPI_Interpolate (our params)", ns,
      "at data " + sci(fit_at_data(curve, t)) + "; " + std::to_string(curve->NbPoles()) + " poles");

  // the whole workload: the point array from the flat data, its own parameters, the solve
  auto whole = [&]() {
    Handle(TColgp_HArray1OfPnt) p = fill();
    GeomAPI_Interpolate it(p, Standard_False, 1e-12);
    it.Perform();
    curve = it.Curve();
  };
  ns = median_ns(whole, static_cast<double>(n));
  std::vector<double> s(n, 0.0);
  for (long i = 1; i < n; ++i) {
    double dx = q[3 * i] - q[3 * i - 3], dy = q[3 * i + 1] - q[3 * i - 2], dz = q[3 * i + 2] - q[3 * i - 1];
    s[i] = s[i - 1] + std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  for (double& v : s) v *= curve->LastParameter() / s[n - 1];
  row("interp_" + sn, "OCCT C++ GeomAPI_Interpolate (fill+own params)", ns,
      "whole workload; at data " + sci(fit_at_data(curve, s)));
}

// bicubic interpolation of an n x n grid: GeomAPI_PointsToBSplineSurface::Interpolate, chord
void surface(long n) {
  const std::string sn = std::to_string(n);
  std::vector<double> g = read_f64("surf_q_" + sn + ".bin");
  const int ni = static_cast<int>(n);
  TColgp_Array2OfPnt arr(1, ni, 1, ni);
  auto at = [&](int k, int l) {
    size_t o = 3 * (static_cast<size_t>(k) * n + l);
    return gp_Pnt(g[o], g[o + 1], g[o + 2]);
  };
  for (int k = 0; k < ni; ++k)
    for (int l = 0; l < ni; ++l) arr.SetValue(k + 1, l + 1, at(k, l));
  Handle(Geom_BSplineSurface) s;
  auto solve = [&]() {
    GeomAPI_PointsToBSplineSurface api;
    api.Interpolate(arr, Approx_ChordLength);
    s = api.Surface();
  };
  double ns = median_ns(solve, static_cast<double>(n * n));
  // its knots are its parameters: the fit at a sub-grid of the data
  double err = 0.0;
  int step = std::max(1, ni / 40);
  for (int k = 0; k < ni; k += step)
    for (int l = 0; l < ni; l += step)
      err = std::max(err, s->Value(s->UKnot(k + 1), s->VKnot(l + 1)).Distance(at(k, l)));
  row("surface_" + sn, "OCCT C++ PointsToBSplineSurface::Interpolate", ns,
      "at data " + sci(err / max_abs(g)));
}

// Bezier degree elevation a -> b of one 3-D curve: Geom_BezierCurve::Increase (on a fresh
// curve each time, since it elevates in place; the construction is timed apart in the note)
void elevation(int a, int b) {
  const std::string ab = std::to_string(a) + "_" + std::to_string(b), work = "elevate_" + ab;
  if (b > Geom_BezierCurve::MaxDegree()) {
    std::fprintf(stderr, "occt_bench: %s skipped: Geom_BezierCurve's degree is at most %d\n",
                 work.c_str(), Geom_BezierCurve::MaxDegree());
    return;
  }
  std::vector<double> p = read_f64("elev_in_" + ab + ".bin"), ours = read_f64("elev_out_" + ab + ".bin");
  TColgp_Array1OfPnt poles = poles_of(p);
  Handle(Geom_BezierCurve) c;
  double build = median_ns([&]() { c = new Geom_BezierCurve(poles); }, 1.0);
  double ns = median_ns(
      [&]() {
        c = new Geom_BezierCurve(poles);
        c->Increase(b);
      },
      1.0);
  std::vector<double> got;
  for (int i = 1; i <= c->NbPoles(); ++i) {
    const gp_Pnt& q = c->Pole(i);
    got.insert(got.end(), {q.X(), q.Y(), q.Z()});
  }
  double diff = got.size() == ours.size() ? max_abs_diff(got, ours) : HUGE_VAL;
  char note[96];
  std::snprintf(note, sizeof note, "construct+Increase (construct alone %.2f us); diff %s rel",
                build * 1e-3, sci(diff / max_abs(ours)).c_str());
  row(work, "OCCT C++ Geom_BezierCurve::Increase", ns, note);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 8) {
    std::fprintf(stderr,
                 "usage: occt_bench DATA_DIR REPEATS N_CTRL N INTERP_SIZES SURFACE_SIZES "
                 "ELEVATIONS\n  e.g. occt_bench target/peers-data 7 1000 1000000 "
                 "1000,10000 100,200 '10,20;50,100'\n");
    return 2;
  }
  try {
    g_dir = argv[1];
    g_repeats = std::stoi(argv[2]);
    if (std::stol(argv[4]) > 0) evaluation(std::stoi(argv[3]), std::stol(argv[4]));
    for (long n : parse_list(argv[5], ',')) interpolation(n);
    for (long n : parse_list(argv[6], ',')) surface(n);
    std::stringstream ss(argv[7]);
    std::string item;
    while (std::getline(ss, item, ';')) {
      std::vector<long> ab = parse_list(item, ',');
      if (ab.size() == 2) elevation(static_cast<int>(ab[0]), static_cast<int>(ab[1]));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "occt_bench: %s\n", e.what());
    return 1;
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "occt_bench: Open CASCADE: %s\n", e.GetMessageString());
    return 1;
  }
  return 0;
}
