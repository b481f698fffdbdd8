// haptics._client: the C++ SDK (haptics/client.h) for Python. The package
// haptics (python/haptics/__init__.py) wraps it; errors become
// haptics.Error naming the gRPC status. Calls that may wait on the
// network release the GIL, so that a Watcher's callback (on its own
// thread) can take it meanwhile.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "haptics/client.h"

namespace py = pybind11;

namespace {

// haptics.Error, set by the package at import (_client.set_error_type);
// kept for the life of the process (no destructor runs after Python's end).
py::handle error_type;

[[noreturn]] void Raise(const haptics::Error& error) {
  py::object e = error_type(haptics::CodeName(error.code), error.message);
  PyErr_SetObject(error_type.ptr(), e.ptr());
  throw py::error_already_set();
}

template <typename T>
T Take(haptics::Result<T> result) {
  if (!result.ok()) Raise(result.error());
  return *std::move(result);
}

void Check(const haptics::Error& error) {
  if (!error.ok()) Raise(error);
}

template <size_t N>
py::tuple Tuple(const double (&values)[N]) {
  py::tuple t(N);
  for (size_t i = 0; i < N; ++i) t[i] = values[i];
  return t;
}

template <size_t N>
void Fill(const std::array<double, N>& from, double (&to)[N]) {
  for (size_t i = 0; i < N; ++i) to[i] = from[i];
}

// The Python side's device: the C++ Device and the last tick's flags.
struct PyDevice {
  std::unique_ptr<haptics::Device> device;
  uint32_t flags = 0;

  haptics::Device& get() {
    if (!device) Raise({haptics::Code::kFailedPrecondition, "the device is closed"});
    return *device;
  }
};

struct PyWatcher {
  std::unique_ptr<haptics::Watcher> watcher;

  haptics::Watcher& get() {
    if (!watcher) Raise({haptics::Code::kFailedPrecondition, "the watcher is closed"});
    return *watcher;
  }
};

struct PySession {
  std::unique_ptr<haptics::Session> session;

  haptics::Session& get() {
    if (!session) Raise({haptics::Code::kFailedPrecondition, "the session is closed"});
    return *session;
  }
};

std::string Or(const std::optional<std::string>& s) { return s.value_or(""); }

// Runs `call` (a request that may wait on the network) without the GIL;
// its result is turned into Python objects, or an exception, after.
template <typename F>
auto WithoutGil(F call) {
  py::gil_scoped_release release;
  return call();
}

// Ends a device, watcher or session without the GIL: their threads may be
// waiting for it (a Watcher's callback).
template <typename T>
void Close(std::unique_ptr<T>& held) {
  std::unique_ptr<T> closing = std::move(held);
  py::gil_scoped_release release;
  closing.reset();
}

}  // namespace

PYBIND11_MODULE(_client, m) {
  m.doc() = "The haptic simulation service's client SDK (see the haptics package)";
  m.def("set_error_type", [](py::object type) { error_type = type.release(); });
  m.def("version", [] {
    return std::to_string(HAPTICS_CLIENT_VERSION_MAJOR) + "." +
           std::to_string(HAPTICS_CLIENT_VERSION_MINOR) + "." +
           std::to_string(HAPTICS_CLIENT_VERSION_PATCH);
  });

  py::class_<haptics::Pose>(m, "Pose")
      .def_property_readonly("position", [](const haptics::Pose& p) { return Tuple(p.position_m); })
      .def_property_readonly("orientation",
                             [](const haptics::Pose& p) { return Tuple(p.orientation_wxyz); });
  py::class_<haptics::Contact>(m, "Contact")
      .def_readonly("object", &haptics::Contact::object)
      .def_readonly("colliding", &haptics::Contact::colliding)
      .def_readonly("penetrating", &haptics::Contact::penetrating)
      .def_readonly("depth", &haptics::Contact::depth_m)
      .def_property_readonly("normal", [](const haptics::Contact& c) { return Tuple(c.normal_w); })
      .def_property_readonly("points",
                             [](const haptics::Contact& c) {
                               py::list points;
                               for (size_t i = 0; i + 2 < c.points_w_m.size(); i += 3) {
                                 points.append(py::make_tuple(c.points_w_m[i], c.points_w_m[i + 1],
                                                              c.points_w_m[i + 2]));
                               }
                               return points;
                             })
      .def_property_readonly("time_of_impact", [](const haptics::Contact& c) -> py::object {
        if (c.time_of_impact < 0) return py::none();
        return py::float_(c.time_of_impact);
      });
  py::class_<haptics::Plane>(m, "Plane")
      .def_readonly("object", &haptics::Plane::object)
      .def_property_readonly("point", [](const haptics::Plane& p) { return Tuple(p.point_w_m); })
      .def_property_readonly("normal", [](const haptics::Plane& p) { return Tuple(p.normal_w); })
      .def_readonly("gap", &haptics::Plane::gap_m)
      .def_readonly("stiffness", &haptics::Plane::stiffness_n_per_m)
      .def_readonly("damping", &haptics::Plane::damping_ns_per_m)
      .def_readonly("separating", &haptics::Plane::separating);
  py::class_<haptics::LocalModel>(m, "LocalModel")
      .def_readonly("revision", &haptics::LocalModel::revision)
      .def_readonly("proxy_pose", &haptics::LocalModel::proxy_pose)
      .def_readonly("validity_radius", &haptics::LocalModel::validity_radius_m)
      .def_readonly("force_clamp", &haptics::LocalModel::force_clamp_n)
      .def_readonly("touching", &haptics::LocalModel::touching)
      .def_readonly("planes", &haptics::LocalModel::planes);
  py::class_<haptics::ToolFrame>(m, "ToolFrame")
      .def_readonly("tool", &haptics::ToolFrame::tool)
      .def_readonly("holder", &haptics::ToolFrame::holder)
      .def_readonly("device_pose", &haptics::ToolFrame::device_pose)
      .def_readonly("proxy_pose", &haptics::ToolFrame::proxy_pose)
      .def_property_readonly("force", [](const haptics::ToolFrame& t) { return Tuple(t.force_n); })
      .def_property_readonly("torque",
                             [](const haptics::ToolFrame& t) { return Tuple(t.torque_nm); })
      .def_readonly("force_clamped", &haptics::ToolFrame::force_clamped)
      .def_readonly("contacts", &haptics::ToolFrame::contacts)
      .def_property_readonly("local_model", [](const haptics::ToolFrame& t) -> py::object {
        if (!t.has_local_model) return py::none();
        return py::cast(t.local_model);
      });
  py::class_<haptics::Frame>(m, "Frame")
      .def_readonly("step", &haptics::Frame::step)
      .def_readonly("time", &haptics::Frame::time_s)
      .def_readonly("dropped_frames", &haptics::Frame::dropped_frames)
      .def_readonly("missed_steps", &haptics::Frame::missed_steps)
      .def_readonly("tools", &haptics::Frame::tools);
  py::class_<haptics::SceneInfo>(m, "SceneInfo")
      .def_readonly("name", &haptics::SceneInfo::name)
      .def_readonly("step", &haptics::SceneInfo::step)
      .def_readonly("step_s", &haptics::SceneInfo::step_s)
      .def_readonly("triangles", &haptics::SceneInfo::triangles)
      .def_readonly("devices", &haptics::SceneInfo::devices)
      .def_readonly("viewers", &haptics::SceneInfo::viewers)
      .def_readonly("revision", &haptics::SceneInfo::revision);
  py::class_<haptics::ModelInfo>(m, "ModelInfo")
      .def_readonly("model_id", &haptics::ModelInfo::model_id)
      .def_readonly("vertices", &haptics::ModelInfo::vertices)
      .def_readonly("triangles", &haptics::ModelInfo::triangles);
  py::class_<haptics::DeviceState>(m, "DeviceState")
      .def_readonly("connected", &haptics::DeviceState::connected)
      .def_readonly("round_trip_s", &haptics::DeviceState::round_trip_s)
      .def_readonly("model_age_s", &haptics::DeviceState::model_age_s)
      .def_readonly("beyond_validity_ticks", &haptics::DeviceState::beyond_validity_ticks)
      .def_readonly("reconnects", &haptics::DeviceState::reconnects)
      .def_readonly("frames", &haptics::DeviceState::frames)
      .def_readonly("models", &haptics::DeviceState::models)
      .def_readonly("rejected_poses", &haptics::DeviceState::rejected_poses)
      .def_readonly("closed", &haptics::DeviceState::closed)
      .def_property_readonly("last_error", [](const haptics::DeviceState& s) -> py::object {
        if (s.last_error.ok()) return py::none();
        return py::str(s.last_error.ToString());
      });

  py::class_<PyDevice>(m, "Device")
      .def(
          "tick",
          [](PyDevice& self, std::array<double, 3> position, std::array<double, 4> orientation) {
            haptics::Pose pose;
            Fill(position, pose.position_m);
            Fill(orientation, pose.orientation_wxyz);
            const haptics::TickOutput out = self.get().Tick(pose);
            if (!out.ok()) {
              Raise({haptics::Code::kInvalidArgument,
                     "a pose's numbers must be finite and its quaternion unit"});
            }
            self.flags = out.flags;
            return py::make_tuple(Tuple(out.force_n), Tuple(out.torque_nm));
          },
          py::arg("position"), py::arg("orientation") = std::array<double, 4>{1, 0, 0, 0})
      .def_property_readonly("flags", [](const PyDevice& self) { return self.flags; })
      .def("state", [](PyDevice& self) { return self.get().State(); })
      .def("close", [](PyDevice& self) { Close(self.device); })
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PyDevice& self, py::args) { Close(self.device); });

  py::class_<PyWatcher>(m, "Watcher")
      .def("latest",
           [](PyWatcher& self) -> py::object {
             haptics::Frame frame;
             if (!self.get().Latest(&frame)) return py::none();
             return py::cast(std::move(frame));
           })
      .def_property_readonly("frames", [](PyWatcher& self) { return self.get().frames(); })
      .def_property_readonly("ended", [](PyWatcher& self) { return self.get().ended(); })
      .def("status",
           [](PyWatcher& self) -> py::object {
             const haptics::Error error = self.get().status();
             if (error.ok()) return py::none();
             return py::str(error.ToString());
           })
      .def("close", [](PyWatcher& self) { Close(self.watcher); })
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PyWatcher& self, py::args) { Close(self.watcher); });

  py::class_<PySession>(m, "Session")
      .def("health",
           [](PySession& self) {
             haptics::Session& session = self.get();
             return Take(WithoutGil([&] { return session.Health(); }));
           })
      .def("scenes",
           [](PySession& self) {
             haptics::Session& session = self.get();
             return Take(WithoutGil([&] { return session.ListScenes(); }));
           })
      .def(
          "create_scene",
          [](PySession& self, const std::string& path, const std::optional<std::string>& name) {
            haptics::Session& session = self.get();
            return Take(WithoutGil([&] { return session.CreateScene(path, Or(name)); }));
          },
          py::arg("path"), py::arg("name") = py::none())
      .def(
          "replace_scene",
          [](PySession& self, const std::string& path, const std::optional<std::string>& name) {
            haptics::Session& session = self.get();
            return Take(WithoutGil([&] { return session.ReplaceScene(path, Or(name)); }));
          },
          py::arg("path"), py::arg("name") = py::none())
      .def(
          "delete_scene",
          [](PySession& self, const std::string& name) {
            haptics::Session& session = self.get();
            Check(WithoutGil([&] { return session.DeleteScene(name); }));
          },
          py::arg("name"))
      .def(
          "upload_model",
          [](PySession& self, const std::string& path, const std::optional<std::string>& name) {
            haptics::Session& session = self.get();
            return Take(WithoutGil([&] { return session.UploadModel(path, Or(name)); }));
          },
          py::arg("path"), py::arg("name") = py::none())
      .def(
          "delete_model",
          [](PySession& self, const std::string& model_id) {
            haptics::Session& session = self.get();
            Check(WithoutGil([&] { return session.DeleteModel(model_id); }));
          },
          py::arg("model_id"))
      .def(
          "device",
          [](PySession& self, const std::string& scene, const std::string& tool, double rate_hz,
             double frame_rate_hz, bool local_model, double max_passivity_damping, double tick_s,
             bool take_over, double open_timeout) {
            haptics::Session& session = self.get();
            haptics::DeviceOptions options;
            options.rate_hz = rate_hz;
            options.frame_rate_hz = frame_rate_hz;
            options.local_model = local_model;
            options.max_passivity_damping_ns_per_m = max_passivity_damping;
            options.tick_s = tick_s;
            options.take_over = take_over;
            options.open_timeout_s = open_timeout;
            return PyDevice{
                Take(WithoutGil([&] { return session.OpenDevice(scene, tool, options); }))};
          },
          py::arg("scene"), py::arg("tool"), py::kw_only(), py::arg("rate_hz") = 250.0,
          py::arg("frame_rate_hz") = 0.0, py::arg("local_model") = true,
          py::arg("max_passivity_damping") = 30.0, py::arg("tick_s") = 1e-3,
          py::arg("take_over") = false, py::arg("open_timeout") = 0.0)
      .def(
          "watch",
          [](PySession& self, const std::string& scene, bool poses, bool contacts, bool forces,
             bool local_model, double frame_rate_hz, std::optional<py::function> on_frame,
             double open_timeout) {
            haptics::Session& session = self.get();
            haptics::WatchOptions options;
            options.poses = poses;
            options.contacts = contacts;
            options.forces = forces;
            options.local_model = local_model;
            options.frame_rate_hz = frame_rate_hz;
            options.open_timeout_s = open_timeout;
            if (on_frame) {
              // Called on the Watcher's thread: take the GIL; an exception
              // the callback raises is reported and the stream goes on.
              // The last copy may go on a thread without the GIL.
              std::shared_ptr<py::function> callback(new py::function(*std::move(on_frame)),
                                                     [](py::function* f) {
                                                       py::gil_scoped_acquire gil;
                                                       delete f;
                                                     });
              options.on_frame = [callback](const haptics::Frame& frame) {
                py::gil_scoped_acquire gil;
                try {
                  (*callback)(frame);
                } catch (py::error_already_set& e) {
                  e.discard_as_unraisable("haptics watch callback");
                }
              };
            }
            return PyWatcher{
                Take(WithoutGil([&] { return session.Watch(scene, std::move(options)); }))};
          },
          py::arg("scene"), py::kw_only(), py::arg("poses") = true, py::arg("contacts") = true,
          py::arg("forces") = true, py::arg("local_model") = false, py::arg("frame_rate_hz") = 0.0,
          py::arg("on_frame") = py::none(), py::arg("open_timeout") = 0.0)
      .def("close", [](PySession& self) { Close(self.session); })
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PySession& self, py::args) { Close(self.session); });

  m.def(
      "connect",
      [](const std::string& address, std::optional<std::string> tls_ca,
         std::optional<std::string> tls_cert, std::optional<std::string> tls_key,
         std::optional<std::string> tls_server_name, std::optional<std::string> token,
         std::optional<std::string> token_file, double connect_timeout, double call_timeout) {
        haptics::SessionOptions options;
        options.tls.ca_file = Or(tls_ca);
        options.tls.cert_file = Or(tls_cert);
        options.tls.key_file = Or(tls_key);
        options.tls.server_name = Or(tls_server_name);
        options.token = Or(token);
        options.token_file = Or(token_file);
        options.connect_timeout_s = connect_timeout;
        options.call_timeout_s = call_timeout;
        return PySession{
            Take(WithoutGil([&] { return haptics::Session::Connect(address, options); }))};
      },
      py::arg("address"), py::kw_only(), py::arg("tls_ca") = py::none(),
      py::arg("tls_cert") = py::none(), py::arg("tls_key") = py::none(),
      py::arg("tls_server_name") = py::none(), py::arg("token") = py::none(),
      py::arg("token_file") = py::none(), py::arg("connect_timeout") = 5.0,
      py::arg("call_timeout") = 10.0);
}
