#include "server/scene_service.h"

#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <thread>

#include "common/hash/sha256.h"
#include "tests/server/test_server.h"

namespace hs::testing {
namespace {

using google::protobuf::util::MessageDifferencer;

// An OBJ cube, 2 cm on a side.
const char kCubeObj[] =
    "v 0 0 0\nv 0.02 0 0\nv 0.02 0.02 0\nv 0 0.02 0\n"
    "v 0 0 0.02\nv 0.02 0 0.02\nv 0.02 0.02 0.02\nv 0 0.02 0.02\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

// Uploads `data` in chunks of `chunk_bytes`, announcing `sha256`.
pb::SceneObject UploadedObject(const std::string& name, const std::string& model_id) {
  pb::SceneObject o;
  o.set_name(name);
  o.set_kind(pb::OBJECT_KIND_FIXED);
  o.mutable_model()->set_uploaded_model_id(model_id);
  *o.mutable_pose() = PoseAt(0.3, 0, 0);
  return o;
}

// Scenes are created, listed, read, changed and deleted through the API;
// a model bigger than one 4 MiB message uploads in chunks and becomes an
// object; each accepted change raises the revision.
TEST(SceneServiceTest, LifecycleAndLargeUpload) {
  TestServer server;
  server.Create(SmallScene("a"));
  server.Create(SmallScene("b"));
  pb::ListScenesResponse list;
  ASSERT_TRUE(server.scenes().ListScenes(ContextWithin(10).get(), {}, &list).ok());
  ASSERT_EQ(list.scenes_size(), 2);
  EXPECT_EQ(list.scenes(0).spec().name(), "a");

  // OBJ comments pad the file past 4 MiB: the transport is what is tested.
  std::string obj = kCubeObj;
  while (obj.size() < (5u << 20)) obj += "# padding padding padding padding padding padding\n";
  pb::UploadModelResponse uploaded;
  const grpc::Status upload =
      UploadModel(server.scenes(), "cube", "obj", obj, Sha256Of(obj), 1 << 20, &uploaded);
  ASSERT_TRUE(upload.ok()) << upload.error_message();
  EXPECT_EQ(uploaded.model_id(), "cube.obj");
  EXPECT_EQ(uploaded.triangles(), 12);

  const int64_t triangles = server.Get("a").triangles();
  pb::AddObjectRequest add;
  add.set_scene("a");
  *add.mutable_object() = UploadedObject("block", "cube.obj");
  pb::SceneInfo info;
  ASSERT_TRUE(server.scenes().AddObject(ContextWithin(10).get(), add, &info).ok());
  EXPECT_EQ(info.triangles(), triangles + 12);
  EXPECT_EQ(info.revision(), 1);

  pb::UpdateObjectRequest update;
  update.set_scene("a");
  update.set_object("block");
  *update.mutable_pose() = PoseAt(0.4, 0, 0);
  update.set_set_materials(true);
  update.add_materials()->mutable_material()->set_stiffness_n_per_m(500);
  pb::VertexMove* move = update.add_vertex_moves();
  move->set_vertex_id(0);
  move->mutable_position_m()->set_z(-0.001);
  ASSERT_TRUE(server.scenes().UpdateObject(ContextWithin(10).get(), update, &info).ok());
  EXPECT_EQ(info.spec().objects(2).pose().position_m().x(), 0.4);
  EXPECT_EQ(info.spec().objects(2).vertex_moves_size(), 1);
  EXPECT_EQ(info.spec().objects(2).materials(0).material().stiffness_n_per_m(), 500);

  pb::SetEffectsRequest effects;
  effects.set_scene("a");
  effects.add_effects(pb::EFFECT_COLLISION);
  ASSERT_TRUE(server.scenes().SetEffects(ContextWithin(10).get(), effects, &info).ok());
  EXPECT_EQ(info.spec().effects_size(), 1);

  pb::RemoveObjectRequest remove;
  remove.set_scene("a");
  remove.set_object("block");
  ASSERT_TRUE(server.scenes().RemoveObject(ContextWithin(10).get(), remove, &info).ok());
  EXPECT_EQ(info.spec().objects_size(), 2);
  EXPECT_EQ(info.revision(), 4);

  pb::DeleteSceneRequest del;
  del.set_scene("b");
  pb::DeleteSceneResponse deleted;
  ASSERT_TRUE(server.scenes().DeleteScene(ContextWithin(10).get(), del, &deleted).ok());
  pb::GetSceneRequest get;
  get.set_scene("b");
  EXPECT_EQ(server.scenes().GetScene(ContextWithin(10).get(), get, &info).error_code(),
            grpc::StatusCode::NOT_FOUND);
}

// Every SceneService RPC given bad input answers with its specific code,
// and the scene reads back exactly as before (spec and revision).
TEST(SceneServiceTest, BadInputGetsSpecificCodeAndChangesNothing) {
  ServerLimits limits;
  limits.max_scenes = 2;
  limits.max_triangles_per_scene = 5000;
  TestServer server(limits);
  server.Create(SmallScene("s"));
  const pb::SceneInfo before = server.Get("s");
  const double nan = std::nan("");
  pb::SceneInfo info;
  using Call = std::function<grpc::Status()>;
  auto add = [&](const pb::SceneObject& object, const std::string& scene = "s") -> Call {
    return [&server, object, scene] {
      pb::AddObjectRequest request;
      request.set_scene(scene);
      *request.mutable_object() = object;
      pb::SceneInfo out;
      return server.scenes().AddObject(ContextWithin(10).get(), request, &out);
    };
  };
  auto update = [&](const pb::UpdateObjectRequest& request) -> Call {
    return [&server, request] {
      pb::SceneInfo out;
      return server.scenes().UpdateObject(ContextWithin(10).get(), request, &out);
    };
  };
  auto create = [&](const pb::SceneSpec& spec) -> Call {
    return [&server, spec] {
      pb::CreateSceneRequest request;
      *request.mutable_spec() = spec;
      pb::SceneInfo out;
      return server.scenes().CreateScene(ContextWithin(10).get(), request, &out);
    };
  };
  auto upload = [&](const std::string& name, const std::string& data, const std::string& sha) {
    return [&server, name, data, sha] {
      pb::UploadModelResponse out;
      return UploadModel(server.scenes(), name, "obj", data, sha, 64, &out);
    };
  };

  pb::SceneObject nan_pose = UploadedObject("x", "none.obj");
  nan_pose.mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_x(0.1);
  *nan_pose.mutable_pose() = PoseAt(nan, 0, 0);
  pb::SceneObject bad_box = nan_pose;
  *bad_box.mutable_pose() = PoseAt(0, 0, 0);
  bad_box.mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_y(-1);
  pb::SceneObject huge_box = bad_box;
  huge_box.mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_y(1e308);
  huge_box.mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_z(1e308);
  pb::SceneObject file_model = bad_box;
  file_model.mutable_model()->set_path("/etc/passwd");
  pb::SceneObject sphere = bad_box;
  sphere.mutable_model()->mutable_procedural()->mutable_sphere()->set_radius_m(0.1);
  sphere.mutable_model()->mutable_procedural()->mutable_sphere()->set_subdivisions(5);
  pb::SceneObject taken = bad_box;
  taken.set_name("table");
  taken.mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_y(0.1);
  taken.mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_z(0.1);

  pb::UpdateObjectRequest unknown_object;
  unknown_object.set_scene("s");
  unknown_object.set_object("ghost");
  pb::UpdateObjectRequest bad_quaternion;
  bad_quaternion.set_scene("s");
  bad_quaternion.set_object("table");
  *bad_quaternion.mutable_pose() = PoseAt(0, 0, 0);
  bad_quaternion.mutable_pose()->mutable_orientation()->set_w(0.9);
  pb::UpdateObjectRequest bad_material = bad_quaternion;
  bad_material.clear_pose();
  bad_material.set_set_materials(true);
  bad_material.add_materials()->mutable_material()->set_stiffness_n_per_m(nan);
  pb::UpdateObjectRequest bad_vertex = bad_quaternion;
  bad_vertex.clear_pose();
  bad_vertex.add_vertex_moves()->set_vertex_id(100000);
  pb::UpdateObjectRequest inf_vertex = bad_vertex;
  inf_vertex.mutable_vertex_moves(0)->set_vertex_id(0);
  inf_vertex.mutable_vertex_moves(0)->mutable_position_m()->set_x(INFINITY);

  pb::SceneSpec nan_scene = SmallScene("t");
  nan_scene.set_step_s(nan);
  pb::SceneSpec too_fast = SmallScene("t");
  too_fast.set_step_s(1e-7);
  pb::SceneSpec too_big = SmallScene("t");
  *too_big.add_objects() = sphere;

  const std::string cube = kCubeObj;
  const std::string garbage = "this is not a mesh\n";
  const std::vector<std::pair<grpc::StatusCode, Call>> cases = {
      {grpc::StatusCode::INVALID_ARGUMENT, create(nan_scene)},
      {grpc::StatusCode::INVALID_ARGUMENT, create(too_fast)},
      {grpc::StatusCode::ALREADY_EXISTS, create(SmallScene("s"))},
      {grpc::StatusCode::PERMISSION_DENIED,
       [&, s = SmallScene("t")]() mutable {
         *s.add_objects() = file_model;
         return create(s)();
       }},
      {grpc::StatusCode::RESOURCE_EXHAUSTED, create(too_big)},
      {grpc::StatusCode::NOT_FOUND,
       [&] {
         pb::GetSceneRequest r;
         r.set_scene("ghost");
         return server.scenes().GetScene(ContextWithin(10).get(), r, &info);
       }},
      {grpc::StatusCode::NOT_FOUND,
       [&] {
         pb::DeleteSceneRequest r;
         r.set_scene("ghost");
         pb::DeleteSceneResponse out;
         return server.scenes().DeleteScene(ContextWithin(10).get(), r, &out);
       }},
      {grpc::StatusCode::NOT_FOUND, add(bad_box, "ghost")},
      {grpc::StatusCode::INVALID_ARGUMENT, add(nan_pose)},
      {grpc::StatusCode::INVALID_ARGUMENT, add(bad_box)},
      {grpc::StatusCode::INVALID_ARGUMENT, add(huge_box)},
      {grpc::StatusCode::ALREADY_EXISTS, add(taken)},
      {grpc::StatusCode::PERMISSION_DENIED, add(file_model)},
      {grpc::StatusCode::NOT_FOUND, add(UploadedObject("y", "none.obj"))},
      {grpc::StatusCode::RESOURCE_EXHAUSTED, add(sphere)},
      {grpc::StatusCode::NOT_FOUND, update(unknown_object)},
      {grpc::StatusCode::INVALID_ARGUMENT, update(bad_quaternion)},
      {grpc::StatusCode::INVALID_ARGUMENT, update(bad_material)},
      {grpc::StatusCode::INVALID_ARGUMENT, update(bad_vertex)},
      {grpc::StatusCode::INVALID_ARGUMENT, update(inf_vertex)},
      {grpc::StatusCode::NOT_FOUND,
       [&] {
         pb::RemoveObjectRequest r;
         r.set_scene("s");
         r.set_object("ghost");
         return server.scenes().RemoveObject(ContextWithin(10).get(), r, &info);
       }},
      {grpc::StatusCode::INVALID_ARGUMENT,
       [&] {
         pb::SetEffectsRequest r;
         r.set_scene("s");
         r.add_effects(static_cast<pb::Effect>(99));
         return server.scenes().SetEffects(ContextWithin(10).get(), r, &info);
       }},
      {grpc::StatusCode::INVALID_ARGUMENT, upload("wrongsum", cube, Sha256Of("other"))},
      {grpc::StatusCode::INVALID_ARGUMENT, upload("garbage", garbage, Sha256Of(garbage))},
      {grpc::StatusCode::INVALID_ARGUMENT, upload("../escape", cube, Sha256Of(cube))},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].second().error_code(), cases[i].first) << "case " << i;
  }
  const pb::SceneInfo after = server.Get("s");
  EXPECT_TRUE(MessageDifferencer::Equals(before.spec(), after.spec()));
  EXPECT_EQ(before.revision(), after.revision());
  EXPECT_EQ(before.triangles(), after.triangles());
  pb::ListScenesResponse list;
  ASSERT_TRUE(server.scenes().ListScenes(ContextWithin(10).get(), {}, &list).ok());
  EXPECT_EQ(list.scenes_size(), 1);
  // Rejections are counted by method and code.
  EXPECT_NE(server.metrics().Text().find("hs_rejected_requests_total{code=\"NOT_FOUND\",method="
                                         "\"GetScene\"} 1"),
            std::string::npos);
}

// Past the server's limits on scenes and objects per scene, requests are
// RESOURCE_EXHAUSTED.
TEST(SceneServiceTest, SceneAndObjectLimits) {
  ServerLimits limits;
  limits.max_scenes = 1;
  limits.max_objects_per_scene = 2;
  TestServer server(limits);
  server.Create(SmallScene("only"));
  pb::CreateSceneRequest create;
  *create.mutable_spec() = SmallScene("second");
  pb::SceneInfo info;
  EXPECT_EQ(server.scenes().CreateScene(ContextWithin(10).get(), create, &info).error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
  pb::AddObjectRequest add;
  add.set_scene("only");
  *add.mutable_object() = SmallScene("x").objects(1);
  add.mutable_object()->set_name("third");
  EXPECT_EQ(server.scenes().AddObject(ContextWithin(10).get(), add, &info).error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(server.Get("only").spec().objects_size(), 2);
}

// Vertex moves grow a scene's spec until it would pass max_spec_bytes:
// that UpdateObject is RESOURCE_EXHAUSTED and changes nothing, revision
// included, and every reply before it fitted; more moves in one request
// than max_vertex_moves_per_request are refused the same way.
TEST(SceneServiceTest, SpecSizeAndVertexMoveLimits) {
  ServerLimits limits;
  limits.max_spec_bytes = 4096;
  limits.max_vertex_moves_per_request = 4;
  TestServer server(limits);
  server.Create(SmallScene("grow"));
  pb::UpdateObjectRequest update;
  update.set_scene("grow");
  update.set_object("table");
  pb::SceneInfo info;
  grpc::Status status;
  int64_t revision = server.Get("grow").revision();
  for (int round = 0; round < 1000; ++round) {
    update.clear_vertex_moves();
    for (int v = 0; v < 4; ++v) {
      pb::VertexMove* move = update.add_vertex_moves();
      move->set_vertex_id(v);
      move->mutable_position_m()->set_x(0.1 + 1e-6 * round);
      move->mutable_position_m()->set_y(0.1);
      move->mutable_position_m()->set_z(0.01 * (v % 2));
    }
    status = server.scenes().UpdateObject(ContextWithin(10).get(), update, &info);
    if (!status.ok()) break;
    EXPECT_LE(info.spec().ByteSizeLong(), 4096u);
    revision = info.revision();
  }
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_EQ(server.Get("grow").revision(), revision);

  const pb::VertexMove move = update.vertex_moves(0);
  update.clear_vertex_moves();
  for (int v = 0; v < 5; ++v) *update.add_vertex_moves() = move;
  EXPECT_EQ(server.scenes().UpdateObject(ContextWithin(10).get(), update, &info).error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(server.Get("grow").revision(), revision);
}

// One caller cannot take what others need: past its own stream and scene
// quotas it is RESOURCE_EXHAUSTED while another caller (here: the same
// peer with a token would be another; on an open server all of this test's
// calls are one peer) is refused only by the server-wide limits.
TEST(SceneServiceTest, PerCallerQuotas) {
  ServerLimits limits;
  limits.per_caller.streams = 2;
  limits.per_caller.scenes = 2;
  TestServer server(limits);
  server.Create(SmallScene("one"));
  server.Create(SmallScene("two"));
  pb::CreateSceneRequest create;
  *create.mutable_spec() = SmallScene("three");
  pb::SceneInfo info;
  const grpc::Status third = server.scenes().CreateScene(ContextWithin(10).get(), create, &info);
  EXPECT_EQ(third.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(third.error_message(), "at most 2 scenes per caller");
  pb::DeleteSceneRequest remove;
  remove.set_scene("two");
  pb::DeleteSceneResponse removed;
  ASSERT_TRUE(server.scenes().DeleteScene(ContextWithin(10).get(), remove, &removed).ok());
  EXPECT_TRUE(server.scenes().CreateScene(ContextWithin(10).get(), create, &info).ok());

  pb::WatchRequest watch;
  watch.set_scene("one");
  std::vector<std::unique_ptr<grpc::ClientContext>> contexts;
  std::vector<std::unique_ptr<grpc::ClientReader<pb::Frame>>> readers;
  pb::Frame frame;
  for (int i = 0; i < 3; ++i) {
    contexts.push_back(ContextWithin(10));
    readers.push_back(server.sessions().Watch(contexts.back().get(), watch));
    const bool got_frame = readers.back()->Read(&frame);
    EXPECT_EQ(got_frame, i < 2) << i;
  }
  EXPECT_EQ(readers.back()->Finish().error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  contexts[0]->TryCancel();
  readers[0]->Finish();
  // The slot comes back once the stream is done (on the server's time).
  bool reopened = false;
  for (int attempt = 0; attempt < 100 && !reopened; ++attempt) {
    auto context = ContextWithin(10);
    auto reader = server.sessions().Watch(context.get(), watch);
    reopened = reader->Read(&frame);
    context->TryCancel();
    reader->Finish();
    if (!reopened) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(reopened);
  contexts[1]->TryCancel();
  readers[1]->Finish();
}

// An uploaded model cannot be deleted while a scene uses it; once no scene
// does, DeleteModel removes it and the id is free for other bytes.
TEST(SceneServiceTest, DeleteModelOnlyWhenUnused) {
  TestServer server;
  const std::string tetrahedron =
      "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  pb::UploadModelResponse uploaded;
  {
    auto context = ContextWithin(10);
    auto writer = server.scenes().UploadModel(context.get(), &uploaded);
    pb::UploadModelChunk chunk;
    chunk.mutable_header()->set_name("tet");
    chunk.mutable_header()->set_format("obj");
    chunk.mutable_header()->set_size_bytes(static_cast<int64_t>(tetrahedron.size()));
    chunk.mutable_header()->set_sha256(Sha256Of(tetrahedron));
    chunk.set_data(tetrahedron);
    writer->Write(chunk);
    writer->WritesDone();
    ASSERT_TRUE(writer->Finish().ok());
  }
  pb::SceneSpec spec = SmallScene("uses");
  spec.mutable_objects(0)->mutable_model()->set_uploaded_model_id("tet.obj");
  server.Create(spec);
  pb::DeleteModelRequest request;
  request.set_model_id("tet.obj");
  pb::DeleteModelResponse response;
  const grpc::Status in_use =
      server.scenes().DeleteModel(ContextWithin(10).get(), request, &response);
  EXPECT_EQ(in_use.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_EQ(in_use.error_message(), "model 'tet.obj' is used by object 'table' of scene 'uses'");
  pb::DeleteSceneRequest remove;
  remove.set_scene("uses");
  pb::DeleteSceneResponse removed;
  ASSERT_TRUE(server.scenes().DeleteScene(ContextWithin(10).get(), remove, &removed).ok());
  EXPECT_TRUE(server.scenes().DeleteModel(ContextWithin(10).get(), request, &response).ok());
  EXPECT_EQ(server.scenes().DeleteModel(ContextWithin(10).get(), request, &response).error_code(),
            grpc::StatusCode::NOT_FOUND);
}

// Scene and object names outside the documented set (1..64 of
// [A-Za-z0-9 _.-]) are INVALID_ARGUMENT and nothing is made.
TEST(SceneServiceTest, NamesAreChecked) {
  TestServer server;
  pb::SceneInfo info;
  for (const std::string& name :
       {std::string(65, 'a'), std::string("bad\nname"), std::string("nul\0x", 5),
        std::string(" lead"), std::string("")}) {
    pb::CreateSceneRequest create;
    *create.mutable_spec() = SmallScene(name);
    EXPECT_EQ(server.scenes().CreateScene(ContextWithin(10).get(), create, &info).error_code(),
              grpc::StatusCode::INVALID_ARGUMENT);
    *create.mutable_spec() = SmallScene("ok name-1.2_x");
    create.mutable_spec()->mutable_objects(0)->set_name(name);
    EXPECT_EQ(server.scenes().CreateScene(ContextWithin(10).get(), create, &info).error_code(),
              grpc::StatusCode::INVALID_ARGUMENT);
  }
  pb::ListScenesResponse listed;
  ASSERT_TRUE(server.scenes().ListScenes(ContextWithin(10).get(), {}, &listed).ok());
  EXPECT_EQ(listed.scenes_size(), 0);
  server.Create(SmallScene("ok name-1.2_x"));
}

// A tool held by a device cannot be removed (FAILED_PRECONDITION) and the
// scene stays as it was.
TEST(SceneServiceTest, HeldToolCannotBeRemoved) {
  TestServer server;
  server.Create(SmallScene("held"));
  auto context = ContextWithin(30);
  auto stream = server.sessions().Interact(context.get());
  pb::InteractRequest open;
  open.mutable_open()->set_scene("held");
  open.mutable_open()->set_tool("probe");
  stream->Write(open);
  pb::Frame frame;
  ASSERT_TRUE(stream->Read(&frame));
  const pb::SceneInfo before = server.Get("held");
  ASSERT_EQ(before.claimed_tools_size(), 1);

  pb::RemoveObjectRequest remove;
  remove.set_scene("held");
  remove.set_object("probe");
  pb::SceneInfo info;
  EXPECT_EQ(server.scenes().RemoveObject(ContextWithin(10).get(), remove, &info).error_code(),
            grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_TRUE(MessageDifferencer::Equals(before.spec(), server.Get("held").spec()));
  stream->WritesDone();
  while (stream->Read(&frame)) {
  }
  EXPECT_TRUE(stream->Finish().ok());
}

// GetGeometry returns each object's HDS: closed boxes, so Euler's formula
// (V - E + F = 2) holds, every edge joins two vertices of some face, the
// table is at its pose; after a vertex move the revision is GetScene's and
// the vertex is where it was moved. An unknown scene is NOT_FOUND.
TEST(SceneServiceTest, GeometryIsTheSceneHds) {
  TestServer server;
  server.Create(SmallScene("geo"));
  auto geometry = [&](const std::string& scene, pb::SceneGeometry& out) {
    pb::GetGeometryRequest request;
    request.set_scene(scene);
    return server.scenes().GetGeometry(ContextWithin(10).get(), request, &out);
  };
  pb::SceneGeometry got;
  ASSERT_TRUE(geometry("geo", got).ok());
  ASSERT_EQ(got.objects_size(), 2);
  EXPECT_EQ(got.scene(), "geo");
  for (const pb::ObjectGeometry& o : got.objects()) {
    SCOPED_TRACE(o.name());
    const int v = o.vertices_m_size() / 3, f = o.triangles_size() / 3, e = o.edges_size() / 2;
    EXPECT_EQ(v - e + f, 2);
    EXPECT_EQ(o.face_materials_size(), f);
    std::set<std::pair<int, int>> face_edges;
    for (int i = 0; i < f; ++i) {
      for (int k = 0; k < 3; ++k) {
        const int a = o.triangles(3 * i + k), b = o.triangles(3 * i + (k + 1) % 3);
        face_edges.insert({std::min(a, b), std::max(a, b)});
      }
    }
    for (int i = 0; i < e; ++i) {
      EXPECT_TRUE(face_edges.count({o.edges(2 * i), o.edges(2 * i + 1)})) << "edge " << i;
    }
  }
  EXPECT_EQ(got.objects(0).name(), "table");
  EXPECT_EQ(got.objects(0).kind(), pb::OBJECT_KIND_FIXED);
  EXPECT_EQ(got.objects(1).kind(), pb::OBJECT_KIND_TOOL);

  pb::UpdateObjectRequest update;
  update.set_scene("geo");
  update.set_object("table");
  pb::VertexMove* move = update.add_vertex_moves();
  move->set_vertex_id(0);
  move->mutable_position_m()->set_z(-0.05);
  pb::SceneInfo info;
  ASSERT_TRUE(server.scenes().UpdateObject(ContextWithin(10).get(), update, &info).ok());
  ASSERT_TRUE(geometry("geo", got).ok());
  EXPECT_EQ(got.revision(), server.Get("geo").revision());
  EXPECT_EQ(got.objects(0).vertices_m(2), -0.05);
  EXPECT_EQ(geometry("missing", got).error_code(), grpc::StatusCode::NOT_FOUND);
}

// A change whose build outlasts the call's deadline is not applied: the
// caller gets DEADLINE_EXCEEDED and the scene never appears.
TEST(SceneServiceTest, BuildPastDeadlineChangesNothing) {
  TestServer server;
  pb::SceneSpec slow = SmallScene("slow");
  pb::Procedural::Torus* torus =
      slow.mutable_objects(0)->mutable_model()->mutable_procedural()->mutable_torus();
  torus->set_major_radius_m(0.2);
  torus->set_minor_radius_m(0.05);
  torus->set_major_segments(200);
  torus->set_minor_segments(200);
  pb::CreateSceneRequest request;
  *request.mutable_spec() = slow;
  pb::SceneInfo info;
  EXPECT_EQ(server.scenes().CreateScene(ContextWithin(0.02).get(), request, &info).error_code(),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  // Changes run one at a time: once this one is done, so is the slow one.
  server.Create(SmallScene("after"));
  pb::ListScenesResponse list;
  ASSERT_TRUE(server.scenes().ListScenes(ContextWithin(10).get(), {}, &list).ok());
  ASSERT_EQ(list.scenes_size(), 1);
  EXPECT_EQ(list.scenes(0).spec().name(), "after");
}

// Changes while a device streams keep the stream, the step ids (no
// restart) and the tool where the device put it.
TEST(SceneServiceTest, ChangesKeepStreamsStepsAndToolPoses) {
  TestServer server;
  server.Create(SmallScene("live"));
  auto context = ContextWithin(30);
  auto stream = server.sessions().Interact(context.get());
  pb::InteractRequest request;
  request.mutable_open()->set_scene("live");
  request.mutable_open()->set_tool("probe");
  stream->Write(request);
  request.mutable_pose()->set_sequence(1);
  *request.mutable_pose()->mutable_pose() = PoseAt(0.01, 0, 0.04);
  stream->Write(request);
  pb::Frame frame;
  while (stream->Read(&frame) && frame.last_pose_sequence() < 1) {
  }
  const int64_t step_before = frame.step();

  pb::AddObjectRequest add;
  add.set_scene("live");
  pb::SceneObject* ball = add.mutable_object();
  ball->set_name("ball");
  ball->set_kind(pb::OBJECT_KIND_FIXED);
  ball->mutable_model()->mutable_procedural()->mutable_sphere()->set_radius_m(0.01);
  *ball->mutable_pose() = PoseAt(0.5, 0, 0);
  pb::SceneInfo info;
  ASSERT_TRUE(server.scenes().AddObject(ContextWithin(10).get(), add, &info).ok());
  for (int n = 0; n < 20; ++n) ASSERT_TRUE(stream->Read(&frame));
  EXPECT_GT(frame.step(), step_before + 19);
  ASSERT_EQ(frame.tools_size(), 1);
  EXPECT_DOUBLE_EQ(frame.tools(0).device_pose().position_m().x(), 0.01);
  EXPECT_DOUBLE_EQ(frame.tools(0).device_pose().position_m().z(), 0.04);
  stream->WritesDone();
  while (stream->Read(&frame)) {
  }
  EXPECT_TRUE(stream->Finish().ok());
}

}  // namespace
}  // namespace hs::testing
