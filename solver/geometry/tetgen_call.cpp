// The TetGen call and its child-process isolation. TetGen is built as a library (TETLIBRARY):
// it throws an int.
#define TETLIBRARY
#include "solver/geometry/tetgen_call.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tetgen.h>
#include <unistd.h>

#include "solver/core/clock.hpp"
#include "solver/core/error.hpp"

namespace asperity::geometry {
namespace {

constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

std::string tetgen_error(int code) {
  switch (code) {
    case 1:
      return "out of memory";
    case 2:
      return "internal error";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "a feature of the surface is below TetGen's tolerance (very small)";
    case 5:
      return "two surface faces are too close to each other";
    case 10:
      return "invalid input";
    default:
      return "error code " + std::to_string(code);
  }
}

std::array<int, 3> sorted(int a, int b, int c) {
  std::array<int, 3> t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

// Faces of the tetrahedra that belong to one tetrahedron only, as sorted triples.
std::vector<std::array<int, 3>> boundary_faces(const Eigen::Matrix4Xi& tets) {
  std::vector<std::array<int, 3>> all;
  all.reserve(4 * static_cast<std::size_t>(tets.cols()));
  for (Eigen::Index t = 0; t < tets.cols(); ++t)
    for (const auto& f : kFace) all.push_back(sorted(tets(f[0], t), tets(f[1], t), tets(f[2], t)));
  std::sort(all.begin(), all.end());
  std::vector<std::array<int, 3>> once;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j] == all[i]) ++j;
    if (j - i == 1) once.push_back(all[i]);
    i = j;
  }
  return once;
}

std::string switches_of(const TetgenJob& job) {
  std::ostringstream sw;
  sw << "pYzQ";
  if (job.radius_edge_ratio > 0) {
    sw << "q" << job.radius_edge_ratio;
    if (job.min_dihedral_deg > 0) sw << "/" << job.min_dihedral_deg;
  }
  if (!job.point_sizes.empty()) sw << "m";
  if (job.max_steiner_points >= 0) sw << "S" << job.max_steiner_points;
  return sw.str();
}

}  // namespace

// The failed check in an assert() message ("tetgen: tetgen.cxx:12345: int tetgenmesh::f(...):
// Assertion `x' failed."): ": tetgen.cxx:12345, in tetgenmesh::f, `x'", or "" when the
// child's stderr holds none.
std::string tetgen_assertion(const std::string& errors) {
  const std::size_t at = errors.find("Assertion `");
  if (at == std::string::npos) return "";
  const std::size_t end = errors.find('\'', at + 11);
  const std::string check = errors.substr(at + 10, end == std::string::npos ? 80 : end - at - 9);
  std::size_t line_start = errors.rfind('\n', at);
  line_start = line_start == std::string::npos ? 0 : line_start + 1;
  std::string where = errors.substr(line_start, at - line_start);
  // "prog: file:line: signature: " -> "file:line" and the function's name
  std::string file_line, function;
  if (const std::size_t c = where.find(": "); c != std::string::npos) {
    const std::string rest = where.substr(c + 2);
    const std::size_t c2 = rest.find(':', rest.find(':') + 1);
    file_line = rest.substr(0, c2);
    if (const std::size_t slash = file_line.rfind('/'); slash != std::string::npos)
      file_line.erase(0, slash + 1);
    const std::size_t paren = rest.find('(', c2);
    const std::size_t name = rest.rfind(' ', paren);
    if (paren != std::string::npos && name != std::string::npos && name > c2)
      function = rest.substr(name + 1, paren - name - 1);
  }
  std::string out = ": ";
  if (!file_line.empty()) out += file_line + ", ";
  if (!function.empty()) out += "in " + function + ", ";
  return out + check;
}

TetMesh run_tetgen(const TetgenJob& job) {
  const SurfaceMesh& surface = job.surface;
  const int n = static_cast<int>(surface.vertices.cols());
  const int nf = static_cast<int>(surface.faces.cols());
  const int nl = static_cast<int>(job.extra_points.size());
  const int nw = static_cast<int>(job.internal_facets.size());
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = n + nl;
  in.pointlist = new REAL[3 * static_cast<std::size_t>(n + nl)];
  std::memcpy(in.pointlist, surface.vertices.data(),
              sizeof(REAL) * 3 * static_cast<std::size_t>(n));
  for (int k = 0; k < nl; ++k)
    for (int d = 0; d < 3; ++d) in.pointlist[3 * (n + k) + d] = job.extra_points[k](d);
  if (!job.point_sizes.empty()) {
    ASPERITY_CHECK(static_cast<int>(job.point_sizes.size()) == n + nl);
    in.numberofpointmtrs = 1;
    in.pointmtrlist = new REAL[static_cast<std::size_t>(n + nl)];
    std::copy(job.point_sizes.begin(), job.point_sizes.end(), in.pointmtrlist);
  }
  in.numberoffacets = nf + nw;
  in.facetlist = new tetgenio::facet[static_cast<std::size_t>(nf + nw)];
  const auto set_facet = [&](int i, int a, int b, int c) {
    tetgenio::facet& f = in.facetlist[i];
    tetgenio::init(&f);
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&f.polygonlist[0]);
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist = new int[3]{a, b, c};
  };
  for (int i = 0; i < nf; ++i)
    set_facet(i, surface.faces(0, i), surface.faces(1, i), surface.faces(2, i));
  for (int k = 0; k < nw; ++k)
    set_facet(nf + k, job.internal_facets[k][0], job.internal_facets[k][1],
              job.internal_facets[k][2]);
  std::string switches = switches_of(job);
  try {
    ::tetrahedralize(switches.data(), &in, &out);
  } catch (int code) {
    throw std::runtime_error("TetGen failed (switches " + switches + "): " + tetgen_error(code));
  }
  ASPERITY_CHECK(out.numberofcorners == 4 && out.numberofpoints >= n + nl);

  TetMesh tm;
  tm.nodes = Eigen::Map<const Eigen::Matrix3Xd>(out.pointlist, 3, out.numberofpoints);
  if (tm.nodes.leftCols(n) != surface.vertices) {
    throw std::runtime_error("TetGen reordered or moved the surface vertices (switches " +
                             switches + ")");
  }
  for (int k = 0; k < nl; ++k) {
    if (tm.nodes.col(n + k) != job.extra_points[k]) {
      throw std::runtime_error("TetGen reordered or moved the lift apexes (switches " + switches +
                               ")");
    }
  }
  tm.tets = Eigen::Map<const Eigen::Matrix4Xi>(out.tetrahedronlist, 4, out.numberoftetrahedra);
  for (Eigen::Index t = 0; t < tm.tets.cols(); ++t) {
    const Vec3 a = tm.nodes.col(tm.tets(0, t));
    const double six_v = (tm.nodes.col(tm.tets(1, t)) - a)
                             .cross(tm.nodes.col(tm.tets(2, t)) - a)
                             .dot(tm.nodes.col(tm.tets(3, t)) - a);
    if (six_v < 0) std::swap(tm.tets(2, t), tm.tets(3, t));
  }
  tm.surface = surface.faces;

  // The promise of switch Y, checked: the tetrahedra's boundary is the input triangles.
  std::vector<std::array<int, 3>> input(static_cast<std::size_t>(nf));
  for (int i = 0; i < nf; ++i)
    input[i] = sorted(surface.faces(0, i), surface.faces(1, i), surface.faces(2, i));
  std::sort(input.begin(), input.end());
  if (boundary_faces(tm.tets) != input) {
    throw std::runtime_error("TetGen changed the surface triangles (switches " + switches + ")");
  }
  return tm;
}

long steiner_points(const TetgenJob& job, const TetMesh& mesh) {
  return static_cast<long>(mesh.nodes.cols() - job.surface.vertices.cols()) -
         static_cast<long>(job.extra_points.size());
}

IsolatedResult run_tetgen_isolated(const TetgenJob& job, double seconds) {
  IsolatedResult result;
  int fd[2];
  if (pipe(fd) != 0) {
    result.mesh = run_tetgen(job);
    return result;
  }
  int err[2] = {-1, -1};
  if (pipe(err) != 0) err[0] = err[1] = -1;
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    for (const int f : {fd[0], fd[1], err[0], err[1]})
      if (f >= 0) close(f);
    result.mesh = run_tetgen(job);
    return result;
  }
  const auto write_all = [](int f, const void* data, std::size_t bytes) {
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
      const ssize_t w = write(f, p, bytes);
      if (w <= 0) return false;
      p += w;
      bytes -= static_cast<std::size_t>(w);
    }
    return true;
  };
  if (pid == 0) {  // child: mesh, send, and leave without running the parent's exit handlers
    // An interrupted parent (SIGINT, SIGTERM) must not leave TetGen meshing on alone for up to
    // its time budget: the child goes with it (and at once if the parent is already gone).
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(1);
    close(fd[0]);
    // TetGen's assert message is the parent's to summarise, not to print: it goes to the
    // parent through its own pipe, and names the failed check in the parent's one line.
    if (err[0] >= 0) close(err[0]);
    if (err[1] >= 0) {
      dup2(err[1], STDERR_FILENO);
      close(err[1]);
    } else if (const int null = open("/dev/null", O_WRONLY); null >= 0) {
      dup2(null, STDERR_FILENO);
    }
    int code = 1;
    std::string why;
    TetMesh tm;
    try {
      tm = run_tetgen(job);
      code = 0;
    } catch (const std::exception& e) {
      why = e.what();
    }
    const std::int64_t head[3] = {
        code, code == 0 ? tm.nodes.cols() : 0,
        code == 0 ? tm.tets.cols() : static_cast<std::int64_t>(why.size())};
    bool sent = write_all(fd[1], head, sizeof head);
    if (code == 0) {
      sent = sent &&
             write_all(fd[1], tm.nodes.data(),
                       sizeof(double) * 3 * static_cast<std::size_t>(head[1])) &&
             write_all(fd[1], tm.tets.data(), sizeof(int) * 4 * static_cast<std::size_t>(head[2]));
    } else {
      sent = sent && write_all(fd[1], why.data(), why.size());
    }
    close(fd[1]);
    _exit(sent ? 0 : 1);
  }
  close(fd[1]);
  if (err[1] >= 0) close(err[1]);
  // Both pipes are read until the child closes them (it exits), so that neither can fill and
  // stall it; of its stderr the first 4 KiB are kept.
  std::string bytes, errors;
  char buf[1 << 16];
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(std::max(seconds, 0.0));
  pollfd p[2] = {{.fd = fd[0], .events = POLLIN, .revents = 0},
                 {.fd = err[0], .events = POLLIN, .revents = 0}};
  while (p[0].fd >= 0 || p[1].fd >= 0) {
    const double left =
        std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    const int ready =
        left > 0 ? poll(p, 2, static_cast<int>(std::min(left, 3600.0) * 1000) + 1) : 0;
    if (ready == 0) {
      result.timed_out = true;
      kill(pid, SIGKILL);
      break;
    }
    if (ready < 0) break;
    for (int k = 0; k < 2; ++k) {
      if (p[k].fd < 0 || p[k].revents == 0) continue;
      const ssize_t r = read(p[k].fd, buf, sizeof buf);
      if (r <= 0) {
        close(p[k].fd);
        p[k].fd = -1;  // poll skips a negative descriptor
      } else if (k == 0) {
        bytes.append(buf, static_cast<std::size_t>(r));
      } else if (errors.size() < 4096) {
        errors.append(buf, std::min(static_cast<std::size_t>(r), 4096 - errors.size()));
      }
    }
  }
  for (const pollfd& q : p)
    if (q.fd >= 0) close(q.fd);
  // The child's CPU is in none of this thread's clocks: its own usage (wait4's, that child's
  // alone) goes to the thread's waited-for children, so that whoever times this thread's work
  // (a study case, a mesh) counts the meshing, a killed child's spent budget too.
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) == pid) {
    add_waited_child_cpu(static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                         1e-6 *
                             static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec));
  }
  if (result.timed_out) {
    result.failure = "TetGen did not finish within its time budget of " +
                     std::to_string(static_cast<long>(seconds)) + " s";
    return result;
  }
  std::int64_t head[3];
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || bytes.size() < sizeof head) {
    result.failure = WIFSIGNALED(status)
                         ? "TetGen stopped on signal " + std::to_string(WTERMSIG(status)) +
                               " (an internal assertion" + tetgen_assertion(errors) + ")"
                         : "TetGen's child process failed";
    return result;
  }
  std::memcpy(head, bytes.data(), sizeof head);
  if (head[0] != 0) {
    result.failure = bytes.substr(sizeof head, static_cast<std::size_t>(head[2]));
    return result;
  }
  const std::size_t need = sizeof head + sizeof(double) * 3 * static_cast<std::size_t>(head[1]) +
                           sizeof(int) * 4 * static_cast<std::size_t>(head[2]);
  if (bytes.size() != need) {
    result.failure = "TetGen's child process sent a truncated mesh";
    return result;
  }
  TetMesh tm;
  tm.nodes.resize(3, head[1]);
  tm.tets.resize(4, head[2]);
  std::memcpy(tm.nodes.data(), bytes.data() + sizeof head, sizeof(double) * 3 * head[1]);
  std::memcpy(tm.tets.data(), bytes.data() + sizeof head + sizeof(double) * 3 * head[1],
              sizeof(int) * 4 * head[2]);
  tm.surface = job.surface.faces;
  result.mesh = std::move(tm);
  return result;
}

}  // namespace asperity::geometry
