// The mesh bodies a process has prepared (prepared_meshes.hpp).
#include "solver/run/prepared_meshes.hpp"

#include <cstddef>
#include <cstdint>
#include <exception>
#include <future>
#include <list>
#include <map>
#include <mutex>
#include <utility>

#include "solver/core/clock.hpp"
#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"
#if ASPERITY_HAVE_GEOMETRY
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/morton_node_order.hpp"
#endif

namespace asperity::run {
namespace {

#if ASPERITY_HAVE_GEOMETRY
// Mesh files up to this size are kept with their meshes (the key holds the file's bytes).
constexpr std::uintmax_t kMaxKeyBytes = 64u << 20;

// The mesh bodies this process has prepared. One `asperity validate` or `asperity study` meshes
// the same file with the same keys in several scenes (the 2000-vertex hull dropped straight and
// oblique in validation/cases/polyhedra, 7 s of set-up each; a study's rigid and rigid-penalty
// cases at one resolution), and the pipeline is deterministic: a later scene takes the tetrahedra
// the first one made, bit for bit those it would have made itself. A scene that asks while another
// is still making them waits for them. Meshes past kKeptBytes are dropped, oldest first; a file
// over kMaxKeyBytes, or one that cannot be read, is not kept (the pipeline then names its problem).
//
// What a kept mesh cost its maker (the maker thread's CPU in make(), its TetGen children's with
// it) is kept with it, and a thread that takes it adds that to its kept_mesh_cpu
// (kept_mesh_cpu_seconds): a study case timed by its thread's CPU then costs what it would cost
// alone, whichever case of the same mesh ran first (the study's rigid and rigid-penalty cases share
// theirs: the second measured 0.018 s instead of 1.9 s at 2000 faces, 0.6 % of its cost, before
// this).
thread_local double kept_mesh_cpu = 0;

class PreparedMeshes {
 public:
  // The tetrahedra for `key`, made by make() unless this process has them.
  template <class Make>
  TetMesh get(MeshKey key, const Make& make) {
    std::promise<Made> promise;
    std::shared_future<Made> mesh;
    Entries::iterator mine;
    bool maker = false;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      mine = meshes_.find(key);
      if (mine == meshes_.end()) {
        mesh = promise.get_future().share();
        mine = meshes_.emplace(std::move(key), Entry{.mesh = mesh}).first;
        order_.push_back(mine);
        maker = true;
      } else {
        mesh = mine->second.mesh;
      }
    }
    if (!maker) {
      try {
        const Made& made = mesh.get();
        kept_mesh_cpu += made.cpu_seconds;
        return made.tets;
      } catch (...) {  // the maker's error names the maker's scene: this scene finds its own
        return make();
      }
    }
    try {
      const double cpu0 = thread_and_children_cpu_seconds();
      TetMesh tets = make();
      promise.set_value({.tets = tets, .cpu_seconds = thread_and_children_cpu_seconds() - cpu0});
      const std::lock_guard<std::mutex> lock(mutex_);
      mine->second.kept_bytes =
          mine->first.bytes.size() + static_cast<std::size_t>(tets.nodes.size()) * sizeof(double) +
          static_cast<std::size_t>(tets.tets.size() + tets.surface.size()) * sizeof(int);
      kept_ += mine->second.kept_bytes;
      // Drop the oldest made meshes (never one still being made) past the bound.
      for (auto it = order_.begin(); kept_ > kKeptBytes && it != order_.end();) {
        if ((*it)->second.kept_bytes == 0) {
          ++it;
          continue;
        }
        kept_ -= (*it)->second.kept_bytes;
        meshes_.erase(*it);
        it = order_.erase(it);
      }
      return tets;
    } catch (...) {
      promise.set_exception(std::current_exception());
      const std::lock_guard<std::mutex> lock(mutex_);
      std::erase(order_, mine);
      meshes_.erase(mine);
      throw;
    }
  }

 private:
  struct Made {
    TetMesh tets;
    double cpu_seconds = 0;  // the maker thread's CPU in make(), its TetGen children's with it
  };
  struct Entry {
    std::shared_future<Made> mesh;
    std::size_t kept_bytes = 0;  // the key's and the mesh's; 0 while being made
  };
  using Entries = std::map<MeshKey, Entry>;
  static constexpr std::size_t kKeptBytes = std::size_t{256} << 20;

  std::mutex mutex_;
  Entries meshes_;
  std::list<Entries::iterator> order_;  // oldest first
  std::size_t kept_ = 0;
};
#endif

}  // namespace

MeshKey mesh_key(const scene::MeshShape& m, bool deformable) {
  MeshKey k{.faces = m.faces,
            .scale = m.scale,
            .element_size = m.element_size,
            .focused = m.element_size_focus.has_value(),
            .focus_radius = m.element_size_focus_radius,
            .growth = m.element_size_growth,
            .far = m.element_size_far,
            .deformable = deformable};
  if (m.element_size_focus) {
    k.focus = {m.element_size_focus->x(), m.element_size_focus->y(), m.element_size_focus->z()};
  }
  return k;
}

// `deformable`: the body's tetrahedra are finite elements. Only then does the mesher's repair of
// elements that set a short step (own-apex lifting, TetOptions::min_element_step_ratio and
// min_mean_edge_step_ratio) pay: a
// rigid or fixed body's tetrahedra carry no elastic waves, and the repair doubled the set-up of a
// 2000-vertex rigid hull (validation/cases/polyhedra: 7 -> 15 s) for nothing.
TetMesh mesh_body(const scene::MeshShape& m, const std::string& key, bool deformable) {
#if ASPERITY_HAVE_GEOMETRY
  geometry::PipelineOptions o;
  o.faces = m.faces;
  o.read.scale = m.scale;
  o.tetrahedralize = true;
  if (!deformable) o.tet.min_element_step_ratio = o.tet.min_mean_edge_step_ratio = 0;
  o.tet.element_size.size = m.element_size;
  if (m.element_size_focus) {
    o.tet.element_size.focus = *m.element_size_focus;
    o.tet.element_size.focus_radius = m.element_size_focus_radius;
    o.tet.element_size.growth = m.element_size_growth;
    o.tet.element_size.far = m.element_size_far;
  }
  o.element_size_key = key + "shape.element_size";
  // The pipeline keeps the surface's vertices first (node i is vertex i); a deformable body's
  // world needs no such numbering, and its element loop runs faster with nodes close in space
  // close in memory (geometry/morton_node_order.hpp: the same results to the bit). A rigid body
  // has no element loop, and its mass properties are sums over its nodes: it keeps its numbering.
  const auto make = [&] {
    TetMesh t = geometry::prepare_particle(m.file, o).tets;
    if (deformable) geometry::number_nodes_along_morton_curve(t);
    return t;
  };
  MeshKey mesh_key = run::mesh_key(m, deformable);
  try {
    mesh_key.bytes = io::read_input_file(m.file, kMaxKeyBytes);
  } catch (const InputError&) {
    return make();
  }
  static PreparedMeshes prepared;
  return prepared.get(std::move(mesh_key), make);
#else
  (void)m;
  (void)deformable;
  throw InputError(key +
                   "shape: mesh bodies need the geometry pipeline (solver/geometry), "
                   "which is not in this build");
#endif
}

double kept_mesh_cpu_seconds() {
#if ASPERITY_HAVE_GEOMETRY
  return kept_mesh_cpu;
#else
  return 0;
#endif
}

}  // namespace asperity::run
