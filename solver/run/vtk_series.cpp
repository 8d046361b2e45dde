// ParaView time series (run/vtk_series.hpp): which steps become frames, and what a frame holds.
#include "solver/run/vtk_series.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <system_error>

#include "solver/core/error.hpp"
#include "solver/fdem/structured_mesh.hpp"
#include "solver/fem/tet_stress.hpp"
#include "solver/io/atomic_file.hpp"

namespace asperity::run {
namespace fs = std::filesystem;
using io::vtk::DataArray;

namespace {

using Clock = std::chrono::steady_clock;

// Adds the wall time of its scope to `seconds`: everything the series does (copies, stresses,
// encoding, writing) counts as the frames' cost.
class Timed {
 public:
  explicit Timed(double& seconds) : seconds_(seconds), t0_(Clock::now()) {}
  ~Timed() { seconds_ += std::chrono::duration<double>(Clock::now() - t0_).count(); }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;

 private:
  double& seconds_;
  Clock::time_point t0_;
};

std::vector<double> flat(const Eigen::Matrix3Xd& m) {
  return std::vector<double>(m.data(), m.data() + m.size());
}

std::string frame_name(const char* stem, long frame, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%06ld.%s", stem, frame, ext);
  return buf;
}

}  // namespace

FrameFiles::FrameFiles(const VtkOutput& out) : out_(out) {
  // An earlier series in the folder would mix with this one's frames: it goes first.
  std::error_code ec;
  fs::remove_all(out.dir, ec);
  fs::create_directories(out.dir, ec);
  if (ec || ::access(out.dir.c_str(), W_OK) != 0) {
    throw InputError(out.dir.string() + ": --vtk-every: cannot create or write the frame folder" +
                     (ec ? " (" + ec.message() + ")" : ""));
  }
  pvd_.write(out.dir / "run.pvd");  // an empty collection until the first frame is complete
}

void FrameFiles::write_static(const std::string& file, const std::string& xml) {
  io::write_atomically(out_.dir / file, xml);
  static_file_ = file;
  stats_.bytes += static_cast<long long>(xml.size());
}

void FrameFiles::write_frame(double time, const std::string& file, const std::string& xml) {
  io::write_atomically(out_.dir / file, xml);
  pvd_.add(time, file, 0);
  if (!static_file_.empty()) pvd_.add(time, static_file_, 1);
  ++stats_.frames;
  stats_.bytes += static_cast<long long>(xml.size());
  pvd_current_ = false;
  // Rewriting run.pvd after every frame cost as much as the frames themselves (bench_vtk: the
  // rename over the existing file makes ext4 write it out at once, auto_da_alloc): while the run
  // goes on it is rewritten at most once a second, and whole at the end (flush). A run killed
  // mid-way still leaves a collection of whole frames, at most a second behind.
  if (stats_.frames == 1 || Clock::now() - pvd_written_ >= std::chrono::seconds(1)) {
    write_collection();
  }
}

void FrameFiles::flush() {
  if (!pvd_current_) write_collection();
}

void FrameFiles::write_collection() {
  pvd_.write(out_.dir / "run.pvd");
  pvd_written_ = Clock::now();
  pvd_current_ = true;
}

// ---------------------------------------------------------------------------------------------
// FEM/DEM

FdemSeries::FdemSeries(fdem::World& w, const std::vector<Eigen::Matrix4Xi>& body_tets,
                       const VtkOutput& out)
    : files_(out), policy_(out.every) {
  const Timed timed(files_.stats().write_seconds);
  ASPERITY_CHECK(body_tets.size() == w.bodies.size());
  w.keep_contact_force = true;
  w.f_contact = Eigen::Matrix3Xd::Zero(3, w.node_count());  // frame 0: before any contact step

  // Written points: the nodes of the moving bodies, in world order. Fixed bodies go to the static
  // part with their own numbering.
  std::vector<int> local(static_cast<std::size_t>(w.node_count()), -1);
  std::vector<int> fixed_nodes;
  std::vector<int> fixed_local(local.size(), -1);
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    const fdem::Body& body = w.bodies[b];
    for (int i = body.node_begin; i < body.node_end; ++i) {
      if (body.kind == fdem::BodyKind::fixed) {
        fixed_local[static_cast<std::size_t>(i)] = static_cast<int>(fixed_nodes.size());
        fixed_nodes.push_back(i);
      } else {
        local[static_cast<std::size_t>(i)] = static_cast<int>(moving_nodes_.size());
        moving_nodes_.push_back(i);
      }
    }
  }
  std::vector<Eigen::Vector4i> moving, fixed;
  std::vector<int> fixed_body;
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    const fdem::Body& body = w.bodies[b];
    // A deformable body's cells are its elements (their order and orientation), so each cell's
    // stress is its element's.
    const Eigen::Matrix4Xi& tets = body.elements >= 0
                                       ? w.elements[static_cast<std::size_t>(body.elements)].tets
                                       : body_tets[b];
    for (Eigen::Index k = 0; k < tets.cols(); ++k) {
      Eigen::Vector4i t;
      for (int i = 0; i < 4; ++i) {
        const auto g = static_cast<std::size_t>(tets(i, k));
        t[i] = body.kind == fdem::BodyKind::fixed ? fixed_local[g] : local[g];
      }
      if (body.kind == fdem::BodyKind::fixed) {
        fixed.push_back(t);
        fixed_body.push_back(static_cast<int>(b));
      } else {
        moving.push_back(t);
        tet_body_.push_back(static_cast<int>(b));
        tet_element_.push_back(body.elements >= 0 ? static_cast<int>(k) : -1);
      }
    }
  }
  moving_tets_.resize(4, static_cast<Eigen::Index>(moving.size()));
  for (std::size_t k = 0; k < moving.size(); ++k)
    moving_tets_.col(static_cast<Eigen::Index>(k)) = moving[k];
  // What every frame repeats (the format wants the cells in each file) is encoded once here.
  cells_ = io::vtk::tet_cells(moving_tets_, out.encoding);
  body_ids_ = io::vtk::encoded(
      {.name = "body_id", .values = std::vector<std::int32_t>(tet_body_.begin(), tet_body_.end())},
      out.encoding);

  if (!fixed.empty()) {
    Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(fixed_nodes.size()));
    for (std::size_t i = 0; i < fixed_nodes.size(); ++i) {
      x.col(static_cast<Eigen::Index>(i)) = w.x.col(fixed_nodes[i]);
    }
    Eigen::Matrix4Xi t(4, static_cast<Eigen::Index>(fixed.size()));
    for (std::size_t k = 0; k < fixed.size(); ++k) t.col(static_cast<Eigen::Index>(k)) = fixed[k];
    files_.write_static(
        "fixed.vtu",
        io::vtk::unstructured_grid(
            x, t, {},
            {{.name = "body_id",
              .values = std::vector<std::int32_t>(fixed_body.begin(), fixed_body.end())}},
            out.encoding));
  }
  capture(w, 0, frame_state_);
  files_.write_frame(frame_state_.time, frame_name("bodies", frame_++, "vtu"),
                     document(w, frame_state_));
  last_written_step_ = 0;
}

void FdemSeries::capture(const fdem::World& w, long step, State& s) const {
  s.time = w.time;
  s.step = step;
  const auto n = static_cast<Eigen::Index>(moving_nodes_.size());
  s.x.resize(3, n);
  s.v.resize(3, n);
  s.f_contact.resize(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int g = moving_nodes_[static_cast<std::size_t>(i)];
    s.x.col(i) = w.x.col(g);
    s.v.col(i) = w.v.col(g);
    s.f_contact.col(i) = w.f_contact.col(g);
  }
}

std::string FdemSeries::document(const fdem::World& w, const State& s) const {
  const auto n = static_cast<Eigen::Index>(moving_nodes_.size());
  Eigen::Matrix3Xd displacement(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    displacement.col(i) = s.x.col(i) - w.x_initial.col(moving_nodes_[static_cast<std::size_t>(i)]);
  }
  const auto cells = static_cast<std::size_t>(moving_tets_.cols());
  std::vector<double> von_mises(cells, 0.0), energy(cells, 0.0);
  for (std::size_t k = 0; k < cells; ++k) {
    if (tet_element_[k] < 0) continue;  // rigid: no strain
    const fem::TetElements& e = w.elements[static_cast<std::size_t>(
        w.bodies[static_cast<std::size_t>(tet_body_[k])].elements)];
    const auto c = static_cast<Eigen::Index>(k);
    const fem::TetStress st =
        fem::tet_stress(e.law, &e.dm_inv[9 * static_cast<std::size_t>(tet_element_[k])], e.lame,
                        s.x.col(moving_tets_(0, c)), s.x.col(moving_tets_(1, c)),
                        s.x.col(moving_tets_(2, c)), s.x.col(moving_tets_(3, c)));
    von_mises[k] = st.von_mises;
    energy[k] = st.energy_density;
  }
  return io::vtk::unstructured_grid(
      s.x, cells_,
      {{.name = "displacement", .components = 3, .values = flat(displacement)},
       {.name = "velocity", .components = 3, .values = flat(s.v)},
       {.name = "contact_force", .components = 3, .values = flat(s.f_contact)}},
      {{.name = "von_mises", .values = std::move(von_mises)},
       {.name = "strain_energy_density", .values = std::move(energy)},
       body_ids_},
      files_.output().encoding);
}

void FdemSeries::after_step(const fdem::World& w, long k, double force, bool last) {
  const Timed timed(files_.stats().write_seconds);
  if (policy_.new_peak(force)) capture(w, k, peak_);
  if (!policy_.regular(k, last) || k == last_written_step_) return;
  capture(w, k, frame_state_);
  files_.write_frame(w.time, frame_name("bodies", frame_++, "vtu"), document(w, frame_state_));
  last_written_step_ = k;
  if (peak_.step == k) peak_.step = -2;  // already a frame
}

void FdemSeries::finish(const fdem::World& w) {
  const Timed timed(files_.stats().write_seconds);
  // A run that stopped early (unstable) ends on the state where it stopped.
  if (w.steps != last_written_step_) {
    capture(w, w.steps, frame_state_);
    files_.write_frame(w.time, frame_name("bodies", frame_++, "vtu"), document(w, frame_state_));
    last_written_step_ = w.steps;
    if (peak_.step == w.steps) peak_.step = -2;
  }
  if (peak_.step >= 0) {
    files_.write_frame(peak_.time, "bodies_peak.vtu", document(w, peak_));
    peak_.step = -2;
  }
  files_.flush();
}

// ---------------------------------------------------------------------------------------------
// Spheres

SphereSeries::SphereSeries(const dem::SphereWorld& w, const VtkOutput& out)
    : files_(out), policy_(out.every) {
  const Timed timed(files_.stats().write_seconds);
  // Walls as thin blocks of tetrahedra: a box as it is; a plane as a square slab under its
  // point, 4× wider than the farthest sphere from that point (reach 1 m with no sphere).
  std::vector<TetMesh> walls;
  std::vector<std::int32_t> ids;
  for (const dem::Wall& wall : w.walls) {
    TetMesh m;
    if (wall.kind == dem::WallKind::box) {
      m = fdem::box_mesh(wall.a, wall.b, 1, 1, 1);
    } else {
      double reach = 0;
      for (int i = 0; i < w.size(); ++i) {
        reach =
            std::max(reach, (w.x.col(i) - wall.a).norm() + w.radius[static_cast<std::size_t>(i)]);
      }
      const double l = reach > 0 ? 4 * reach : 1.0;
      const Vec3 n = wall.b.normalized(), t1 = n.unitOrthogonal(), t2 = n.cross(t1);
      Mat3 frame;
      frame << t1, t2, n;
      m = fdem::oriented_box_mesh(wall.a, frame, Vec3(-l, -l, -l / 20), Vec3(l, l, 0), 1, 1, 1);
    }
    ids.insert(ids.end(), static_cast<std::size_t>(m.tets.cols()), wall.body);
    walls.push_back(std::move(m));
  }
  if (!walls.empty()) {
    Eigen::Index nodes = 0, tets = 0;
    for (const TetMesh& m : walls) nodes += m.nodes.cols(), tets += m.tets.cols();
    Eigen::Matrix3Xd x(3, nodes);
    Eigen::Matrix4Xi t(4, tets);
    nodes = tets = 0;
    for (const TetMesh& m : walls) {
      x.middleCols(nodes, m.nodes.cols()) = m.nodes;
      t.middleCols(tets, m.tets.cols()) = m.tets.array() + static_cast<int>(nodes);
      nodes += m.nodes.cols(), tets += m.tets.cols();
    }
    files_.write_static(
        "walls.vtu",
        io::vtk::unstructured_grid(x, t, {}, {{.name = "body_id", .values = ids}}, out.encoding));
  }
  radius_ = io::vtk::encoded({.name = "radius", .values = w.radius}, out.encoding);
  body_ids_ = io::vtk::encoded(
      {.name = "body_id", .values = std::vector<std::int32_t>(w.body.begin(), w.body.end())},
      out.encoding);
  const State s0 = capture(w, 0);
  files_.write_frame(s0.time, frame_name("spheres", frame_++, "vtp"), document(w, s0));
  last_written_step_ = 0;
}

SphereSeries::State SphereSeries::capture(const dem::SphereWorld& w, long step) const {
  return {.time = w.time, .step = step, .x = w.x, .v = w.v, .w = w.w, .force = w.force};
}

std::string SphereSeries::document(const dem::SphereWorld& w, const State& s) const {
  return io::vtk::point_cloud(
      s.x,
      {radius_,
       {.name = "displacement", .components = 3, .values = flat(s.x - w.x_initial)},
       {.name = "velocity", .components = 3, .values = flat(s.v)},
       {.name = "angular_velocity", .components = 3, .values = flat(s.w)},
       {.name = "contact_force", .components = 3, .values = flat(s.force)},
       body_ids_},
      files_.output().encoding);
}

void SphereSeries::after_step(const dem::SphereWorld& w, long k, double force, bool last) {
  const Timed timed(files_.stats().write_seconds);
  if (policy_.new_peak(force)) peak_ = capture(w, k);
  if (!policy_.regular(k, last) || k == last_written_step_) return;
  files_.write_frame(w.time, frame_name("spheres", frame_++, "vtp"), document(w, capture(w, k)));
  last_written_step_ = k;
  if (peak_.step == k) peak_.step = -2;
}

void SphereSeries::finish(const dem::SphereWorld& w) {
  const Timed timed(files_.stats().write_seconds);
  // A run that stopped early (unstable) ends on the state where it stopped.
  if (w.steps != last_written_step_) {
    files_.write_frame(w.time, frame_name("spheres", frame_++, "vtp"),
                       document(w, capture(w, w.steps)));
    last_written_step_ = w.steps;
    if (peak_.step == w.steps) peak_.step = -2;
  }
  if (peak_.step >= 0) {
    files_.write_frame(peak_.time, "spheres_peak.vtp", document(w, peak_));
    peak_.step = -2;
  }
  files_.flush();
}

}  // namespace asperity::run
