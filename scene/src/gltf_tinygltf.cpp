// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// glTF 2.0 input through tinygltf (Debian's libtinygltf-dev ships it compiled: no
// TINYGLTF_IMPLEMENTATION here). Images are never decoded.
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/gltf.hpp"
#include "ebgeom/scene/system.hpp"

namespace ebgeom::scene {

namespace {

using Mat4 = std::array<double, 16>; // column-major, as glTF stores it

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 c{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[col * 4 + k];
      c[col * 4 + row] = s;
    }
  return c;
}

double det3(const Mat4& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
         m[8] * (m[1] * m[6] - m[5] * m[2]);
}

class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& m) : path_(path), m_(m) {}

  [[noreturn]] void bad(const std::string& what) const { fail(exit_input, path_ + ": " + what); }

  /// The local transform of node `n`: its matrix, or T * R * S.
  Mat4 local(const tinygltf::Node& n, int index) const {
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16) bad("node " + std::to_string(index) + ": matrix needs 16 values");
      Mat4 out;
      for (int i = 0; i < 16; ++i) out[i] = n.matrix[i];
      return out;
    }
    Mat4 t = identity(), r = identity(), s = identity();
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) bad("node " + std::to_string(index) + ": bad translation");
      t[12] = n.translation[0];
      t[13] = n.translation[1];
      t[14] = n.translation[2];
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) bad("node " + std::to_string(index) + ": bad rotation");
      double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
      const double len = std::sqrt(x * x + y * y + z * z + w * w);
      if (!(len > 0)) bad("node " + std::to_string(index) + ": rotation is not a unit quaternion");
      x /= len, y /= len, z /= len, w /= len;
      r = {1 - 2 * (y * y + z * z),
           2 * (x * y + z * w),
           2 * (x * z - y * w),
           0,
           2 * (x * y - z * w),
           1 - 2 * (x * x + z * z),
           2 * (y * z + x * w),
           0,
           2 * (x * z + y * w),
           2 * (y * z - x * w),
           1 - 2 * (x * x + y * y),
           0,
           0,
           0,
           0,
           1};
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) bad("node " + std::to_string(index) + ": bad scale");
      s[0] = n.scale[0];
      s[5] = n.scale[1];
      s[10] = n.scale[2];
    }
    return mul(t, mul(r, s));
  }

  /// Element `i` of accessor `a` as a pointer into its buffer, after checking the whole range.
  struct View {
    const unsigned char* base = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
  };
  View view(int accessor, const char* what, std::size_t elem_bytes) const {
    const std::string where = std::string(what) + " accessor " + std::to_string(accessor);
    if (accessor < 0 || std::size_t(accessor) >= m_.accessors.size())
      bad(where + " does not exist");
    const tinygltf::Accessor& a = m_.accessors[std::size_t(accessor)];
    if (a.sparse.isSparse) bad(where + " is sparse (not supported)");
    if (a.bufferView < 0 || std::size_t(a.bufferView) >= m_.bufferViews.size())
      bad(where + " has no valid bufferView");
    const tinygltf::BufferView& bv = m_.bufferViews[std::size_t(a.bufferView)];
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= m_.buffers.size())
      bad(where + "'s bufferView has no valid buffer");
    const std::vector<unsigned char>& data = m_.buffers[std::size_t(bv.buffer)].data;
    const std::size_t stride = bv.byteStride ? bv.byteStride : elem_bytes;
    if (stride < elem_bytes) bad(where + ": byteStride smaller than an element");
    View v;
    v.stride = stride;
    v.count = a.count;
    // view range inside the buffer, then the accessor's range inside the view
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
      bad(where + "'s bufferView lies outside its buffer of " + std::to_string(data.size()) +
          " bytes");
    if (a.count > 0) {
      const unsigned long long need = (unsigned long long)a.byteOffset +
                                      (unsigned long long)stride * (a.count - 1) + elem_bytes;
      if (a.count > (std::size_t(1) << 40) || need > bv.byteLength)
        bad(where + ": " + std::to_string(a.count) + " elements do not fit in its bufferView of " +
            std::to_string(bv.byteLength) + " bytes");
    }
    v.base = data.data() + bv.byteOffset + a.byteOffset;
    return v;
  }

  void add_primitive(const tinygltf::Primitive& p, int mesh, const Mat4& xf,
                     PolygonSoup<double>& out) const {
    const std::string where = "mesh " + std::to_string(mesh);
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return; // points and lines have no inside
    const auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) bad(where + ": a primitive without POSITION");
    if (pos->second < 0 || std::size_t(pos->second) >= m_.accessors.size())
      bad(where + ": POSITION accessor does not exist");
    const tinygltf::Accessor& pa = m_.accessors[std::size_t(pos->second)];
    if (pa.type != TINYGLTF_TYPE_VEC3 || pa.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      bad(where + ": POSITION must be float VEC3 (quantized positions are not supported)");
    const View pv = view(pos->second, "POSITION", 12);
    const std::size_t first = out.vertices.size();
    if (first + pv.count >= std::size_t(0xffffffffu)) bad("more vertices than ebgeom indexes");
    for (std::size_t i = 0; i < pv.count; ++i) {
      float q[3];
      std::memcpy(q, pv.base + i * pv.stride, 12);
      if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2]))
        bad(where + ": POSITION " + std::to_string(i) + " is not finite");
      Vec3<double> w;
      for (int r = 0; r < 3; ++r)
        w[r] = xf[r] * q[0] + xf[4 + r] * q[1] + xf[8 + r] * q[2] + xf[12 + r];
      if (!all_finite(w)) bad(where + ": a transformed position is not finite");
      out.vertices.push_back(w);
    }
    std::vector<std::uint32_t> idx;
    if (p.indices >= 0) {
      if (std::size_t(p.indices) >= m_.accessors.size()) bad(where + ": indices do not exist");
      const tinygltf::Accessor& ia = m_.accessors[std::size_t(p.indices)];
      std::size_t size = 0;
      switch (ia.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        size = 1;
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        size = 2;
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        size = 4;
        break;
      default:
        bad(where + ": indices must be unsigned byte, short or int");
      }
      if (ia.type != TINYGLTF_TYPE_SCALAR) bad(where + ": indices must be SCALAR");
      const View iv = view(p.indices, "indices", size);
      idx.resize(iv.count);
      for (std::size_t i = 0; i < iv.count; ++i) {
        const unsigned char* e = iv.base + i * iv.stride;
        std::uint32_t v = 0;
        if (size == 1) v = e[0];
        if (size == 2) {
          std::uint16_t s;
          std::memcpy(&s, e, 2);
          v = s;
        }
        if (size == 4) std::memcpy(&v, e, 4);
        if (v >= pv.count)
          bad(where + ": index " + std::to_string(v) + " (element " + std::to_string(i) +
              ") is past the " + std::to_string(pv.count) + " positions");
        idx[i] = v;
      }
    } else {
      idx.resize(pv.count);
      for (std::size_t i = 0; i < pv.count; ++i) idx[i] = std::uint32_t(i);
    }
    const bool flip = det3(xf) < 0;
    auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (a == b || b == c || a == c) return; // strips use repeated indices as restarts
      const Index A = Index(first + a), B = Index(first + b), C = Index(first + c);
      if (flip)
        out.add_triangle(A, C, B);
      else
        out.add_triangle(A, B, C);
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (idx.size() % 3 != 0)
        bad(where + ": " + std::to_string(idx.size()) + " indices are not whole triangles");
      for (std::size_t i = 0; i + 2 < idx.size(); i += 3) tri(idx[i], idx[i + 1], idx[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < idx.size(); ++i)
        if (i % 2 == 0)
          tri(idx[i], idx[i + 1], idx[i + 2]);
        else
          tri(idx[i + 1], idx[i], idx[i + 2]);
    } else {
      for (std::size_t i = 1; i + 1 < idx.size(); ++i) tri(idx[0], idx[i], idx[i + 1]);
    }
  }

  void add_node(int index, const Mat4& parent, int depth, PolygonSoup<double>& out) const {
    if (index < 0 || std::size_t(index) >= m_.nodes.size())
      bad("node " + std::to_string(index) + " does not exist");
    if (depth > 256) bad("node hierarchy deeper than 256 (a cycle?)");
    const tinygltf::Node& n = m_.nodes[std::size_t(index)];
    const Mat4 xf = mul(parent, local(n, index));
    if (n.mesh >= 0) {
      if (std::size_t(n.mesh) >= m_.meshes.size())
        bad("node " + std::to_string(index) + ": mesh " + std::to_string(n.mesh) +
            " does not exist");
      for (const tinygltf::Primitive& p : m_.meshes[std::size_t(n.mesh)].primitives)
        add_primitive(p, n.mesh, xf, out);
    }
    for (int c : n.children) add_node(c, xf, depth + 1, out);
  }

  PolygonSoup<double> read() const {
    PolygonSoup<double> out;
    std::vector<int> roots;
    if (!m_.scenes.empty()) {
      const int s = m_.defaultScene >= 0 && std::size_t(m_.defaultScene) < m_.scenes.size()
                        ? m_.defaultScene
                        : 0;
      roots = m_.scenes[std::size_t(s)].nodes;
    } else {
      std::vector<bool> child(m_.nodes.size(), false);
      for (const auto& n : m_.nodes)
        for (int c : n.children)
          if (c >= 0 && std::size_t(c) < child.size()) child[std::size_t(c)] = true;
      for (std::size_t i = 0; i < m_.nodes.size(); ++i)
        if (!child[i]) roots.push_back(int(i));
    }
    for (int r : roots) add_node(r, identity(), 0, out);
    if (out.face_count() == 0) bad("no triangles in the scene's meshes");
    return out;
  }

 private:
  const std::string& path_;
  const tinygltf::Model& m_;
};

bool no_images(tinygltf::Image*, const int, std::string*, std::string*, int, int,
               const unsigned char*, int, void*) {
  return true; // geometry only: textures are not decoded
}

} // namespace

bool gltf_available() { return true; }

PolygonSoup<double> read_gltf(const std::string& path) {
  require_input_file(path);
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(no_images, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  std::string lower = path;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool glb = lower.size() > 4 && lower.compare(lower.size() - 4, 4, ".glb") == 0;
  const bool ok = glb ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                      : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    fail(exit_input, path + ": not a readable glTF 2.0 " + (glb ? "binary (.glb)" : "file") +
                         (err.empty() ? std::string() : ": " + err));
  }
  return GltfReader(path, model).read();
}

} // namespace ebgeom::scene
