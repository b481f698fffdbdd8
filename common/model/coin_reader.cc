#include "common/model/coin_reader.h"

#include <array>
#include <bit>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <Inventor/SbMatrix.h>
#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/VRMLnodes/SoVRMLCoordinate.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedShape.h>
#include <Inventor/VRMLnodes/SoVRMLMaterial.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/details/SoFaceDetail.h>
#include <Inventor/elements/SoCoordinateElement.h>
#include <Inventor/elements/SoLazyElement.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoMemoryError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/fields/SoSFBool.h>
#include <Inventor/nodes/SoFaceSet.h>
#include <Inventor/nodes/SoIndexedShape.h>
#include <Inventor/nodes/SoMaterial.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>
#include <Inventor/nodes/SoShapeHints.h>
#include <Inventor/nodes/SoVertexProperty.h>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "common/model/coin_lock.h"

namespace hs {
namespace {

// One line of text from Coin's multi-line error strings.
std::string OneLine(const char* text) {
  return absl::StrJoin(absl::StrSplit(text, absl::ByAnyChar(" \t\r\n"), absl::SkipEmpty()), " ");
}

// Routes every Coin error report to itself while it lives, so that nothing
// is printed and the reports can go into the status; puts the previous
// handlers back when it goes. Only while the Coin lock is held.
class CoinErrorCapture {
 public:
  CoinErrorCapture()
      : read_{SoReadError::getHandlerCallback(), SoReadError::getHandlerData()},
        debug_{SoDebugError::getHandlerCallback(), SoDebugError::getHandlerData()},
        memory_{SoMemoryError::getHandlerCallback(), SoMemoryError::getHandlerData()},
        base_{SoError::getHandlerCallback(), SoError::getHandlerData()} {
    SoReadError::setHandlerCallback(&OnError, this);
    SoDebugError::setHandlerCallback(&OnError, this);
    SoMemoryError::setHandlerCallback(&OnError, this);
    SoError::setHandlerCallback(&OnError, this);
  }
  ~CoinErrorCapture() {
    SoReadError::setHandlerCallback(read_.first, read_.second);
    SoDebugError::setHandlerCallback(debug_.first, debug_.second);
    SoMemoryError::setHandlerCallback(memory_.first, memory_.second);
    SoError::setHandlerCallback(base_.first, base_.second);
  }
  CoinErrorCapture(const CoinErrorCapture&) = delete;
  CoinErrorCapture& operator=(const CoinErrorCapture&) = delete;

  /// True when Coin reported a read or memory error: the file is bad.
  bool failed() const { return !errors_.empty(); }
  /// The errors, then Coin's debug messages (warnings), on one line.
  std::string Text() const {
    std::vector<std::string> all = errors_;
    all.insert(all.end(), notes_.begin(), notes_.end());
    return all.empty() ? "no message from Coin" : absl::StrJoin(all, "; ");
  }

 private:
  using Handler = std::pair<SoErrorCB*, void*>;

  static void OnError(const SoError* error, void* data) {
    auto* self = static_cast<CoinErrorCapture*>(data);
    try {
      std::string text = OneLine(error->getDebugString().getString());
      // Debug messages are Coin's warnings and remarks; a valid file can
      // cause them, so they only explain a failure.
      if (error->isOfType(SoDebugError::getClassTypeId())) {
        self->notes_.push_back(std::move(text));
      } else {
        self->errors_.push_back(std::move(text));
      }
    } catch (...) {
      // Out of memory while keeping a message; the read fails anyway.
    }
  }

  Handler read_, debug_, memory_, base_;
  std::vector<std::string> errors_;
  std::vector<std::string> notes_;
};

// Where a diffuse colour array comes from.
struct MaterialSource {
  const SoNode* node = nullptr;
  int num_values = 0;
};

// Collects the triangles of a scene graph into a RawMesh during one
// SoCallbackAction traversal.
class TriangleCollector {
 public:
  void Attach(SoCallbackAction& action) {
    action.addPreCallback(SoMaterial::getClassTypeId(), &OnMaterial, this);
    action.addPreCallback(SoVRMLMaterial::getClassTypeId(), &OnVrmlMaterial, this);
    action.addPreCallback(SoShape::getClassTypeId(), &OnShape, this);
    action.addTriangleCallback(SoShape::getClassTypeId(), &OnTriangle, this);
  }

  const absl::Status& status() const { return status_; }
  RawMesh TakeMesh() { return std::move(mesh_); }

 private:
  using Response = SoCallbackAction::Response;

  static Response OnMaterial(void* data, SoCallbackAction*, const SoNode* node) {
    auto* self = static_cast<TriangleCollector*>(data);
    const auto* material = static_cast<const SoMaterial*>(node);
    // VRML 1 materials with only an emissive colour use it as the diffuse one.
    return self->Guard([&] {
      self->AddSource(material->diffuseColor.getValues(0), node, material->diffuseColor.getNum());
      self->AddSource(material->emissiveColor.getValues(0), node, material->emissiveColor.getNum());
    });
  }

  static Response OnVrmlMaterial(void* data, SoCallbackAction*, const SoNode* node) {
    auto* self = static_cast<TriangleCollector*>(data);
    const auto* material = static_cast<const SoVRMLMaterial*>(node);
    return self->Guard([&] { self->AddSource(&material->diffuseColor.getValue(), node, 1); });
  }

  static Response OnShape(void* data, SoCallbackAction* action, const SoNode* node) {
    auto* self = static_cast<TriangleCollector*>(data);
    return self->Guard([&] { self->BeginShape(action, node); });
  }

  static void OnTriangle(void* data, SoCallbackAction* action, const SoPrimitiveVertex* v1,
                         const SoPrimitiveVertex* v2, const SoPrimitiveVertex* v3) {
    auto* self = static_cast<TriangleCollector*>(data);
    if (!self->status_.ok()) return;
    self->Guard([&] { self->AddTriangle(action, {v1, v2, v3}); });
  }

  // Runs `body`, turning an exception into a failed status: nothing may
  // unwind through Coin.
  template <typename Body>
  Response Guard(Body body) {
    try {
      body();
    } catch (const std::exception& e) {
      status_ = absl::InvalidArgumentError(absl::StrCat("while collecting triangles: ", e.what()));
    } catch (...) {
      status_ = absl::InvalidArgumentError("unknown exception while collecting triangles");
    }
    return status_.ok() ? SoCallbackAction::CONTINUE : SoCallbackAction::ABORT;
  }

  void AddSource(const SbColor* colors, const SoNode* node, int num_values) {
    if (colors != nullptr && num_values > 0) sources_[colors] = MaterialSource{node, num_values};
  }

  void BeginShape(SoCallbackAction* action, const SoNode* node) {
    shape_vertices_.clear();
    shape_polygons_.clear();
    // VRML 2 geometry declares its winding in a "ccw" field that Coin does
    // not put into the shape hints the action reports.
    SoField* ccw = node->getField(SbName("ccw"));
    shape_clockwise_ = ccw != nullptr && ccw->isOfType(SoSFBool::getClassTypeId()) &&
                       !static_cast<SoSFBool*>(ccw)->getValue();
    status_ = CheckIndices(action, node);
  }

  // Coin reads the coordinates an index names without checking it.
  absl::Status CheckIndices(SoCallbackAction* action, const SoNode* node) const {
    const SoMFInt32* indices = nullptr;
    int64_t num_coordinates = 0;
    if (node->isOfType(SoIndexedShape::getClassTypeId())) {
      const auto* shape = static_cast<const SoIndexedShape*>(node);
      indices = &shape->coordIndex;
      num_coordinates = NumInventorCoordinates(action, shape->vertexProperty.getValue());
    } else if (node->isOfType(SoVRMLIndexedShape::getClassTypeId())) {
      const auto* shape = static_cast<const SoVRMLIndexedShape*>(node);
      indices = &shape->coordIndex;
      const SoNode* coord = shape->coord.getValue();
      if (coord != nullptr && coord->isOfType(SoVRMLCoordinate::getClassTypeId())) {
        num_coordinates = static_cast<const SoVRMLCoordinate*>(coord)->point.getNum();
      }
    } else if (node->isOfType(SoFaceSet::getClassTypeId())) {
      const auto* shape = static_cast<const SoFaceSet*>(node);
      num_coordinates = NumInventorCoordinates(action, shape->vertexProperty.getValue());
      int64_t end = shape->startIndex.getValue();
      for (int i = 0; i < shape->numVertices.getNum(); ++i) {
        // SO_FACE_SET_USE_REST_OF_VERTICES (-1) takes what is left.
        if (shape->numVertices[i] > 0) end += shape->numVertices[i];
      }
      if (shape->startIndex.getValue() < 0 || end > num_coordinates) {
        return absl::InvalidArgumentError(
            absl::StrCat(ShapeName(node), " uses coordinates ", shape->startIndex.getValue(),
                         " .. ", end - 1, " but there are ", num_coordinates));
      }
      return absl::OkStatus();
    }
    if (indices == nullptr) return absl::OkStatus();
    for (int i = 0; i < indices->getNum(); ++i) {
      const int32_t index = (*indices)[i];
      // Any negative index ends a face.
      if (index >= num_coordinates) {
        return absl::InvalidArgumentError(absl::StrCat(ShapeName(node), " coordIndex[", i,
                                                       "] = ", index, " but there are ",
                                                       num_coordinates, " coordinates"));
      }
    }
    return absl::OkStatus();
  }

  static int64_t NumInventorCoordinates(SoCallbackAction* action, const SoNode* vertex_property) {
    if (vertex_property != nullptr &&
        vertex_property->isOfType(SoVertexProperty::getClassTypeId())) {
      const auto* property = static_cast<const SoVertexProperty*>(vertex_property);
      if (property->vertex.getNum() > 0) return property->vertex.getNum();
    }
    return SoCoordinateElement::getInstance(action->getState())->getNum();
  }

  static std::string ShapeName(const SoNode* node) {
    std::string name = node->getTypeId().getName().getString();
    const char* def = node->getName().getString();
    if (def != nullptr && def[0] != '\0') absl::StrAppend(&name, " '", def, "'");
    return name;
  }

  void AddTriangle(SoCallbackAction* action, std::array<const SoPrimitiveVertex*, 3> corners) {
    const SbMatrix& m = action->getModelMatrix();
    // Inventor multiplies row vectors: p_W = [p 1] * M.
    Eigen::Matrix4d X_WS;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) X_WS(c, r) = m[r][c];
    }
    const int32_t material = Material(action, *corners[0]);
    const PolygonId polygon = Polygon(*corners[0]);
    bool reverse = shape_clockwise_ || action->getVertexOrdering() == SoShapeHints::CLOCKWISE;
    if (X_WS.topLeftCorner<3, 3>().determinant() < 0) reverse = !reverse;
    if (reverse) std::swap(corners[1], corners[2]);
    std::array<int32_t, 3> vertices;
    for (int i = 0; i < 3; ++i) vertices[i] = Vertex(corners[i]->getPoint(), X_WS);
    mesh_.AddPolygon(vertices, material, polygon);
  }

  int32_t Vertex(const SbVec3f& p, const Eigen::Matrix4d& X_WS) {
    const std::array<uint32_t, 3> key = {std::bit_cast<uint32_t>(p[0]),
                                         std::bit_cast<uint32_t>(p[1]),
                                         std::bit_cast<uint32_t>(p[2])};
    auto [it, inserted] =
        shape_vertices_.try_emplace(key, static_cast<int32_t>(mesh_.positions.size()));
    if (inserted) {
      const Eigen::Vector4d p_W = X_WS * Eigen::Vector4d(p[0], p[1], p[2], 1.0);
      mesh_.positions.push_back(p_W.head<3>() / p_W.w());
    }
    return it->second;
  }

  PolygonId Polygon(const SoPrimitiveVertex& corner) {
    const SoDetail* detail = corner.getDetail();
    if (detail == nullptr || !detail->isOfType(SoFaceDetail::getClassTypeId())) {
      return next_polygon_++;
    }
    const int face = static_cast<const SoFaceDetail*>(detail)->getFaceIndex();
    auto [it, inserted] = shape_polygons_.try_emplace(face, next_polygon_);
    if (inserted) ++next_polygon_;
    return it->second;
  }

  int32_t Material(SoCallbackAction* action, const SoPrimitiveVertex& corner) {
    const SbColor* diffuse = SoLazyElement::getInstance(action->getState())->getDiffusePointer();
    auto source = sources_.find(diffuse);
    if (source == sources_.end()) return NamedMaterial({nullptr, 0}, "");
    const int index = source->second.num_values > 1 ? corner.getMaterialIndex() : 0;
    const std::pair<const SoNode*, int> key(source->second.node, index);
    if (auto it = materials_.find(key); it != materials_.end()) return it->second;
    std::string name = source->second.node->getName().getString();
    if (name.empty()) {
      name = absl::StrCat("material_", mesh_.material_names.size());
    } else if (source->second.num_values > 1) {
      absl::StrAppend(&name, "_", index);
    }
    return NamedMaterial(key, std::move(name));
  }

  int32_t NamedMaterial(std::pair<const SoNode*, int> key, std::string name) {
    auto [it, inserted] =
        materials_.try_emplace(key, static_cast<int32_t>(mesh_.material_names.size()));
    if (inserted) mesh_.material_names.push_back(std::move(name));
    return it->second;
  }

  RawMesh mesh_;
  absl::Status status_;
  absl::flat_hash_map<const SbColor*, MaterialSource> sources_;
  absl::flat_hash_map<std::pair<const SoNode*, int>, int32_t> materials_;
  // Per traversal of one shape node.
  absl::flat_hash_map<std::array<uint32_t, 3>, int32_t> shape_vertices_;
  absl::flat_hash_map<int, PolygonId> shape_polygons_;
  bool shape_clockwise_ = false;
  PolygonId next_polygon_ = 0;
};

// Releases a node graph read by SoDB::readAll.
struct Unref {
  void operator()(SoNode* node) const { node->unref(); }
};

// Reads the graph `input` is set to (opened by `open`) into a RawMesh.
template <class Open>
absl::StatusOr<RawMesh> ReadLocked(Open open) {
  CoinErrorCapture errors;
  SoInput input;
  if (!open(input)) {
    return absl::InvalidArgumentError(absl::StrCat("Coin cannot open it: ", errors.Text()));
  }
  SoSeparator* root = SoDB::readAll(&input);
  if (root == nullptr || errors.failed()) {
    if (root != nullptr) {
      root->ref();
      root->unref();
    }
    return absl::InvalidArgumentError(absl::StrCat("Coin cannot read it: ", errors.Text()));
  }
  root->ref();
  std::unique_ptr<SoNode, Unref> owner(root);
  TriangleCollector collector;
  SoCallbackAction action;
  collector.Attach(action);
  action.apply(root);
  if (!collector.status().ok()) return collector.status();
  if (errors.failed()) {
    return absl::InvalidArgumentError(absl::StrCat("Coin failed on it: ", errors.Text()));
  }
  return collector.TakeMesh();
}

// ReadLocked under the Coin lock, exceptions caught.
template <class Open>
absl::StatusOr<RawMesh> Read(Open open) {
  try {
    // The lock outlives every Coin object made below.
    std::unique_lock<std::mutex> lock = LockCoin();
    return ReadLocked(open);
  } catch (const std::exception& e) {
    return absl::InvalidArgumentError(absl::StrCat("Coin threw: ", e.what()));
  } catch (...) {
    return absl::InvalidArgumentError("Coin threw an unknown exception");
  }
}

}  // namespace

absl::StatusOr<RawMesh> ReadWithCoin(const std::string& path) {
  return Read([&](SoInput& input) { return input.openFile(path.c_str()) == TRUE; });
}

absl::StatusOr<RawMesh> ReadBytesWithCoin(absl::string_view bytes) {
  return Read([&](SoInput& input) {
    input.setBuffer(bytes.data(), bytes.size());
    return true;
  });
}

}  // namespace hs
