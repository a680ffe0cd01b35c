// Open CASCADE Technology reading a STEP or IGES file, timed in C++ for
// bench/peers/cad_read.py: STEPControl_Reader (or IGESControl_Reader) ReadFile, then
// TransferRoots, which builds the shapes (curves, surfaces and faces) of the file; the median
// wall time and the median CPU time (all threads) of REPEATS whole reads.
//
// Usage: occt_cad_read FILE REPEATS
// Prints one line: seconds <wall> cpu <cpu> roots <n> faces <n> peak_mb <p> (the faces of the
// shape read; the peak resident memory of the process, VmHWM of Linux's /proc/self/status, in
// MB, 0 elsewhere).
// Built by cad_read.py when Debian's libocct-data-exchange-dev (or another OCCT install with
// the headers of TKSTEP and TKIGES) is present.

#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <TopAbs_ShapeEnum.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS_Shape.hxx>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

bool is_iges(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == "igs" || ext == "iges";
}

// CPU time of the process, all threads, in seconds.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The peak resident memory of the process in MB (VmHWM; 0 where /proc/self/status is missing).
double peak_rss_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) * 1024.0 / 1e6;
  }
  return 0.0;
}

struct Timed {
  double wall, cpu;
  int roots, faces;
};

// One whole read, timed (wall and CPU); the faces made are counted after the clocks stop.
template <class Reader>
Timed read(const std::string& path) {
  double c0 = cpu_seconds();
  auto t0 = std::chrono::steady_clock::now();
  Reader r;
  if (r.ReadFile(path.c_str()) != IFSelect_RetDone) {
    std::fprintf(stderr, "occt_cad_read: Open CASCADE cannot read %s\n", path.c_str());
    std::exit(1);
  }
  int roots = r.TransferRoots();
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double cpu = cpu_seconds() - c0;
  int faces = 0;
  for (TopExp_Explorer e(r.OneShape(), TopAbs_FACE); e.More(); e.Next()) ++faces;
  return {wall, cpu, roots, faces};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: occt_cad_read FILE REPEATS\n");
    return 2;
  }
  std::string path = argv[1];
  int repeats = std::max(1, std::atoi(argv[2]));
  // no trace messages on the terminal: they would be timed too
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
  std::vector<double> wall, cpu;
  Timed r{};
  for (int k = 0; k < repeats; ++k) {
    r = is_iges(path) ? read<IGESControl_Reader>(path) : read<STEPControl_Reader>(path);
    wall.push_back(r.wall);
    cpu.push_back(r.cpu);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  std::printf("seconds %.6f cpu %.6f roots %d faces %d peak_mb %.1f\n", wall[wall.size() / 2],
              cpu[cpu.size() / 2], r.roots, r.faces, peak_rss_mb());
  return 0;
}
