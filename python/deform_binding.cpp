// Asset.deform: a clip's frames deformed as `dqskin bake` deforms them, into NumPy arrays written once
// by the deformer's batches (no copy after), in the vertex order of the bake's ply output.
#include "interruptible.hpp"
#include "python_asset.hpp"

#include "../lib/base/byte_size.hpp"
#include "../lib/base/saturating.hpp"
#include "dqskin/animation.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/error.hpp"
#include "dqskin/frame_view.hpp"
#include "dqskin/job.hpp"
#include "../lib/job/job_run.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <variant>

namespace dqskin::python {

namespace py = pybind11;

namespace {

// The clip argument: a clip object (its index), a name, an index, or None for the rest pose.
const Clip* chosen_clip(const Asset& asset, const py::object& clip) {
  if (clip.is_none()) return nullptr;
  std::string which;
  if (py::hasattr(clip, "index") && py::hasattr(clip, "key_times")) which = std::to_string(clip.attr("index").cast<size_t>());
  else if (py::isinstance<py::str>(clip)) which = clip.cast<std::string>();
  else if (py::isinstance<py::int_>(clip) && !py::isinstance<py::bool_>(clip)) {
    const long long index = clip.cast<long long>();
    if (index < 0) throw InputError("clip " + std::to_string(index) + ": an index is at least 0");
    which = std::to_string(index);
  } else {
    throw py::type_error("deform(): clip must be a clip of Asset.clips, a name, an index or None, not " +
                         std::string(py::str(py::type::of(clip).attr("__name__"))));
  }
  if (which == "all") throw InputError("clip: give one clip's name or index, not all");
  return &asset.clips[select_clips(asset, which).front()];  // InputError naming the clips there are
}

// Which of positions, normals and tangents the frames have: normals and tangents where some primitive
// that writes vertices has them (zeros for the others, as the ply writes them).
struct Attributes {
  bool normals = false, tangents = false;
};
Attributes attributes(const LoadedAsset& a) {
  Attributes has;
  size_t p = 0;
  for (const MeshInstance& inst : a.instances)
    for (const Primitive& prim : a.asset.meshes[size_t(inst.mesh)].primitives) {
      if (a.layout.writes(p++)) {
        has.normals = has.normals || !prim.normals.empty();
        has.tangents = has.tangents || !prim.tangents.empty();
      }
    }
  return has;
}

}  // namespace

void register_deform_method(py::class_<PyAsset>& cls) {
  cls.def(
      "deform",
      [](const PyAsset& self, const py::object& clip, std::vector<double> times, const std::string& mode,
         const std::string& backend) {
        const LoadedAsset& a = *self.handle();
        BlendMode blend;
        if (!parse_blend_mode(mode, blend)) throw InputError("mode '" + mode + "' is not one of lbs, dqs, dib");
        Backend where;
        if (!parse_backend(backend, where)) throw InputError(unknown_backend(backend));
        for (double t : times)
          if (!std::isfinite(t)) throw InputError("times: " + std::to_string(t) + " is not a finite time in seconds");
        const Clip* c = nullptr;
        try {
          c = chosen_clip(a.asset, clip);
        } catch (const InputError& e) {
          throw InputError(a.path + ": " + e.what());
        }
        const Attributes has = attributes(a);
        const size_t frames = times.size(), vertices = a.layout.vertices;
        using saturating::mul;
        const uint64_t bytes = mul(mul(frames, vertices), uint64_t(4 * (3 + (has.normals ? 3 : 0) + (has.tangents ? 4 : 0))));
        if (bytes > a.load.max_memory)
          throw InputError(a.path + ": " + std::to_string(frames) + " frames of " + std::to_string(vertices) +
                           " vertices need " + byte_size(bytes) + ", more than max_memory " + byte_size(a.load.max_memory) +
                           "; deform fewer times at once");
        const auto shape = [&](py::ssize_t n) { return std::vector<py::ssize_t>{py::ssize_t(frames), py::ssize_t(vertices), n}; };
        py::array_t<float> positions(shape(3));
        py::object normals = py::none(), tangents = py::none();
        float* pp = positions.mutable_data();
        float* np = nullptr;
        float* tp = nullptr;
        if (has.normals) {
          py::array_t<float> n(shape(3));
          np = n.mutable_data();
          normals = n;
        }
        if (has.tangents) {
          py::array_t<float> t(shape(4));
          tp = t.mutable_data();
          tangents = t;
        }
        run_interruptible([&](const std::atomic<bool>& cancel) {
          JobContext context(where);
          DeformerOptions o;
          o.mode = blend;
          o.backend = where;
          o.before_batch = [&cancel] { check_cancelled(&cancel); };
          const std::unique_ptr<Deformer> deformer = make_deformer(context.for_deforming(blend), a.asset, a.instances, o);
          deformer->run(c, times, [&](const DeformedBatch& batch) {
            check_cancelled(&cancel);  // the GPU deformer has no before_batch
            for (size_t f = 0; f < batch.frame_count; ++f) {
              const size_t frame = batch.first_frame + f;
              size_t v0 = 0;
              for (const PrimitiveView& p : distinct_vertices(frame_view(batch, f), a.layout).primitives) {
                const size_t at = frame * vertices + v0;
                std::memcpy(pp + 3 * at, p.positions.data(), 12 * p.vertices);
                if (np) {
                  if (p.normals.empty()) std::memset(np + 3 * at, 0, 12 * p.vertices);
                  else std::memcpy(np + 3 * at, p.normals.data(), 12 * p.vertices);
                }
                if (tp) {
                  if (p.tangents.empty()) std::memset(tp + 4 * at, 0, 16 * p.vertices);
                  else std::memcpy(tp + 4 * at, p.tangents.data(), 16 * p.vertices);
                }
                v0 += p.vertices;
              }
            }
          });
        });
        py::array_t<double> time_array{py::ssize_t(frames)};
        std::copy(times.begin(), times.end(), time_array.mutable_data());
        return py::module_::import("types").attr("SimpleNamespace")(
            py::arg("times") = time_array, py::arg("positions") = positions, py::arg("normals") = normals,
            py::arg("tangents") = tangents);
      },
      py::arg("clip"), py::arg("times"), py::arg("mode") = "dqs", py::arg("backend") = "auto",
      "deform(clip, times, mode='dqs', backend='auto') -> frames\n\n"
      "Deforms the clip (a clip of Asset.clips, its name or index; None for the rest pose) at `times` (seconds)\n"
      "as `dqskin bake` does, with `mode` lbs, dqs or dib on `backend` auto, egl, osmesa, fast-cpu or cpu.\n"
      "Returns an object with times, positions (frames x vertices x 3, float32, world space), normals\n"
      "(the same shape, or None when no primitive has normals) and tangents (frames x vertices x 4, or None),\n"
      "vertices in the order of the bake's ply output. Ctrl-C stops it within a second.");
}

}  // namespace dqskin::python
