// ParaView time series of a run (`asperity run --vtk-every N`): DIR/vtk/ holds one XML VTK file
// per frame and a run.pvd that lists them with their simulated time. A frame is written every N
// steps, at the last step, and at the recorded body's peak contact force. The series only reads
// the world: writing frames changes no result.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/dem/sphere_world.hpp"
#include "solver/fdem/fdem_world.hpp"
#include "solver/io/vtk_xml.hpp"
#include "solver/run/vtk_output.hpp"

namespace asperity::run {

// The folder, its collection and the bookkeeping every model's series shares. Each file is
// complete (written to a temporary name and renamed) before run.pvd is rewritten to list it.
class FrameFiles {
 public:
  // Throws InputError naming the folder when it cannot be created or written.
  explicit FrameFiles(const VtkOutput& out);
  // A dataset that never changes (fixed blocks, walls), written once and listed at every time.
  void write_static(const std::string& file, const std::string& xml);
  // One frame: its file, then (at most once a second, and for the first frame) the collection.
  void write_frame(double time, const std::string& file, const std::string& xml);
  // The collection, listing every frame written: at the end of the run.
  void flush();
  const VtkOutput& output() const { return out_; }
  const SeriesStats& stats() const { return stats_; }
  SeriesStats& stats() { return stats_; }

 private:
  VtkOutput out_;
  void write_collection();

  io::vtk::Collection pvd_;
  std::string static_file_;
  SeriesStats stats_;
  std::chrono::steady_clock::time_point pvd_written_;
  bool pvd_current_ = true;  // run.pvd lists every frame written so far
};

// Which steps get a frame, and the peak: shared by the models' series.
class FramePolicy {
 public:
  explicit FramePolicy(int every) : every_(every) {}
  bool regular(long k, bool last) const { return last || (every_ > 0 && k % every_ == 0); }
  // True when `force` (N) is a new peak, strictly above every earlier one.
  bool new_peak(double force) {
    if (!(force > peak_)) return false;
    peak_ = force;
    return true;
  }

 private:
  int every_;
  double peak_ = 0;
};

// FEM/DEM: moving bodies (deformable and rigid) in one .vtu per frame; fixed bodies once.
// Point data: displacement (m, from the initial position), velocity (m/s), contact_force (N,
// the node's share of the potential and friction forces). Cell data: von_mises (Pa, Cauchy),
// strain_energy_density (J/m³; 0 for rigid bodies), body_id (the world's body index).
class FdemSeries {
 public:
  // body_tets: each body's tetrahedra in global node indices (world body order). Sets the
  // world's keep_contact_force. Writes the static part and frame 0.
  FdemSeries(fdem::World& w, const std::vector<Eigen::Matrix4Xi>& body_tets, const VtkOutput& out);
  // After step k; `force` the recorded body's contact force magnitude (N); `last`: the run ends.
  void after_step(const fdem::World& w, long k, double force, bool last);
  // Writes the last state unless a frame holds it (a run stopped as unstable), and the peak frame
  // unless a regular frame already holds that step.
  void finish(const fdem::World& w);
  const SeriesStats& stats() const { return files_.stats(); }

 private:
  struct State {
    double time = 0;
    long step = -1;
    Eigen::Matrix3Xd x, v, f_contact;
  };
  // Copies the written points' state into `s` (its buffers reused: the peak is captured at
  // every step of a rising force).
  void capture(const fdem::World& w, long step, State& s) const;
  std::string document(const fdem::World& w, const State& s) const;

  FrameFiles files_;
  FramePolicy policy_;
  std::vector<int> moving_nodes_;  // global node index of each written point
  Eigen::Matrix4Xi moving_tets_;   // in written-point indices
  io::vtk::TetCells cells_;        // moving_tets_, encoded once for every frame
  io::vtk::DataArray body_ids_;    // tet_body_, encoded once
  State frame_state_;              // the state of the frame being written (buffers reused)
  std::vector<int> tet_body_;      // world body of each written tetrahedron
  std::vector<int> tet_element_;   // deformable: element index in its body's TetElements, else -1
  State peak_;
  long last_written_step_ = -1;
  long frame_ = 0;
};

// Spheres: one .vtp per frame, a point per sphere with radius (m), displacement (m), velocity
// (m/s), angular_velocity (rad/s), contact_force (N) and body_id (the scene's body index);
// planes and boxes once, as thin blocks of tetrahedra.
class SphereSeries {
 public:
  SphereSeries(const dem::SphereWorld& w, const VtkOutput& out);
  void after_step(const dem::SphereWorld& w, long k, double force, bool last);
  void finish(const dem::SphereWorld& w);
  const SeriesStats& stats() const { return files_.stats(); }

 private:
  struct State {
    double time = 0;
    long step = -1;
    Eigen::Matrix3Xd x, v, w, force;
  };
  State capture(const dem::SphereWorld& w, long step) const;
  std::string document(const dem::SphereWorld& w, const State& s) const;

  FrameFiles files_;
  FramePolicy policy_;
  io::vtk::DataArray radius_, body_ids_;  // the same in every frame: encoded once
  State peak_;
  long last_written_step_ = -1;
  long frame_ = 0;
};

}  // namespace asperity::run
