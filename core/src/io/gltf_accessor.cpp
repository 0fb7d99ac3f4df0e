// Reading and storing glTF accessor elements of any component type, with bounds checks that name
// the accessor (tinygltf parses the JSON but does not check that accessors fit their buffers).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "io_detail.hpp"

namespace geoshift::io {
namespace {

double loadComponent(const unsigned char* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t v; std::memcpy(&v, p, 1); return v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { uint8_t v; std::memcpy(&v, p, 1); return v; }
    case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); return v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return v; }
    case TINYGLTF_COMPONENT_TYPE_INT: { int32_t v; std::memcpy(&v, p, 4); return v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); return v; }
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: { double v; std::memcpy(&v, p, 8); return v; }
  }
  return 0.0;
}

// glTF 2.0 §3.11: signed normalized values use max(c / (2^(n-1) - 1), -1).
double normalizeComponent(double c, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(c / 127.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return c / 255.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(c / 32767.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return c / 65535.0;
  }
  return c;
}

// Does [begin, begin + bytes) lie inside buffer view `view`, which lies inside its buffer?
// Written with subtractions only: declared offsets and counts may be anything.
void checkRange(const tinygltf::Model& model, int view, size_t begin, size_t bytes,
                const std::string& path, const std::string& where) {
  if (view < 0 || static_cast<size_t>(view) >= model.bufferViews.size())
    fail(path, where + ": buffer view " + std::to_string(view) + " does not exist");
  const auto& bv = model.bufferViews[view];
  if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model.buffers.size())
    fail(path, where + ": buffer view " + std::to_string(view) + " names a missing buffer");
  const size_t size = model.buffers[bv.buffer].data.size();
  if (bv.byteLength > size || bv.byteOffset > size - bv.byteLength)
    fail(path, where + ": buffer view " + std::to_string(view) + " (bytes " + std::to_string(bv.byteOffset) +
                   " to " + formatNumber(static_cast<double>(bv.byteOffset) + static_cast<double>(bv.byteLength)) +
                   ") extends past the end of buffer " + std::to_string(bv.buffer) + " (" + std::to_string(size) +
                   " bytes)");
  if (bytes > bv.byteLength || begin > bv.byteLength - bytes)
    fail(path, where + ": data extends past the end of buffer view " + std::to_string(view));
}

}  // namespace

int componentCount(int type) { return tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)); }

AccessorLayout accessorLayout(const tinygltf::Model& model, int index, const std::string& path,
                              const std::string& where) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
    fail(path, where + ": accessor " + std::to_string(index) + " does not exist");
  const auto& acc = model.accessors[index];
  AccessorLayout l;
  l.components = componentCount(acc.type);
  l.componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType));
  const std::string at = where + " (accessor " + std::to_string(index) + ")";
  if (l.components <= 0 || l.componentSize <= 0) fail(path, at + ": invalid type or component type");
  if (acc.bufferView < 0) return l;
  checkRange(model, acc.bufferView, 0, 0, path, at);
  const auto& bv = model.bufferViews[acc.bufferView];
  const size_t element = static_cast<size_t>(l.components) * l.componentSize;
  // glTF 2.0 schema: byteStride in [4, 252]; a stride shorter than one element overlaps elements.
  if (bv.byteStride != 0 && (bv.byteStride < 4 || bv.byteStride > 252))
    fail(path, at + ": buffer view " + std::to_string(acc.bufferView) + " has byteStride " +
                   std::to_string(bv.byteStride) + " (must be 4 to 252)");
  if (bv.byteStride != 0 && bv.byteStride < element)
    fail(path, at + ": buffer view " + std::to_string(acc.bufferView) + " has byteStride " +
                   std::to_string(bv.byteStride) + ", shorter than the accessor's " + std::to_string(element) +
                   "-byte elements");
  l.buffer = bv.buffer;
  l.stride = bv.byteStride != 0 ? bv.byteStride : element;
  l.offset = bv.byteOffset + acc.byteOffset;
  if (acc.count > 0) {
    // count elements need (count - 1) * stride + element bytes from byteOffset.
    const bool fits = acc.byteOffset <= bv.byteLength && element <= bv.byteLength - acc.byteOffset &&
                      acc.count - 1 <= (bv.byteLength - acc.byteOffset - element) / l.stride;
    if (!fits)
      fail(path, at + ": " + std::to_string(acc.count) + " elements of " + std::to_string(element) +
                     " bytes (stride " + std::to_string(l.stride) + ") from byte " + std::to_string(acc.byteOffset) +
                     " need " +
                     formatNumber(static_cast<double>(acc.byteOffset) +
                                  static_cast<double>(acc.count - 1) * static_cast<double>(l.stride) +
                                  static_cast<double>(element)) +
                     " bytes, but buffer view " + std::to_string(acc.bufferView) + " has " +
                     std::to_string(bv.byteLength));
  }
  return l;
}

std::vector<double> readAccessor(const tinygltf::Model& model, int index, const std::string& path,
                                 const std::string& where, bool normalize, size_t maxWithoutData) {
  const AccessorLayout l = accessorLayout(model, index, path, where);
  const auto& acc = model.accessors[index];
  // Without a buffer view the elements are zeros: nothing in the file bounds their count.
  if (l.buffer < 0 && acc.count > maxWithoutData)
    fail(path, where + " (accessor " + std::to_string(index) + "): no buffer view and " + std::to_string(acc.count) +
                   " elements declared, more than the limit of " + std::to_string(maxWithoutData) +
                   " (raise it with --max-vertices)");
  const bool norm = normalize || acc.normalized;
  const int ct = acc.componentType;
  auto convert = [&](const unsigned char* p) {
    const double c = loadComponent(p, ct);
    return norm ? normalizeComponent(c, ct) : c;
  };
  std::vector<double> out(acc.count * l.components, 0.0);  // no buffer view: zeros (spec)
  if (l.buffer >= 0) {
    const unsigned char* data = model.buffers[l.buffer].data.data() + l.offset;
    for (size_t i = 0; i < acc.count; ++i)
      for (int k = 0; k < l.components; ++k)
        out[i * l.components + k] = convert(data + i * l.stride + k * l.componentSize);
  }
  if (acc.sparse.isSparse) {
    // Sparse accessors are applied on read; writing back stores the result densely.
    const std::string at = where + " (sparse accessor " + std::to_string(index) + ")";
    const size_t n = static_cast<size_t>(std::max(acc.sparse.count, 0));
    const int ict = acc.sparse.indices.componentType;
    const int isz = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(ict));
    if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(path, at + ": sparse indices have component type " + std::to_string(ict) +
                     "; they must be unsigned byte, short or int");
    const size_t elem = static_cast<size_t>(l.components) * l.componentSize;
    if (n > acc.count) fail(path, at + ": " + std::to_string(n) + " sparse elements for " + std::to_string(acc.count));
    checkRange(model, acc.sparse.indices.bufferView, acc.sparse.indices.byteOffset, n * isz, path, at);
    checkRange(model, acc.sparse.values.bufferView, acc.sparse.values.byteOffset, n * elem, path, at);
    const auto& ibv = model.bufferViews[acc.sparse.indices.bufferView];
    const auto& vbv = model.bufferViews[acc.sparse.values.bufferView];
    const unsigned char* idx =
        model.buffers[ibv.buffer].data.data() + ibv.byteOffset + acc.sparse.indices.byteOffset;
    const unsigned char* val =
        model.buffers[vbv.buffer].data.data() + vbv.byteOffset + acc.sparse.values.byteOffset;
    for (size_t s = 0; s < n; ++s) {
      const double t = loadComponent(idx + s * isz, ict);
      if (!(t >= 0 && t < static_cast<double>(acc.count)))
        fail(path, at + ": sparse index " + formatNumber(t) + " out of range (" + std::to_string(acc.count) + " elements)");
      const auto target = static_cast<size_t>(t);
      for (int k = 0; k < l.components; ++k)
        out[target * l.components + k] = convert(val + s * elem + k * l.componentSize);
    }
  }
  return out;
}

void storeComponent(unsigned char* dst, int componentType, bool normalized, double v) {
  // Normalized integers map [0,1] (unsigned) or [-1,1] (signed) onto the full integer range.
  auto integer = [&](double scale, double lo, double hi) {
    const double s = normalized ? std::clamp(v, lo < 0 ? -1.0 : 0.0, 1.0) * scale : v;
    return std::clamp(std::round(s), lo, hi);
  };
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      const float f = static_cast<float>(v);
      std::memcpy(dst, &f, 4);
      return;
    }
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: std::memcpy(dst, &v, 8); return;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const auto c = static_cast<uint8_t>(integer(255, 0, 255));
      std::memcpy(dst, &c, 1);
      return;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto c = static_cast<int8_t>(integer(127, -128, 127));
      std::memcpy(dst, &c, 1);
      return;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const auto c = static_cast<uint16_t>(integer(65535, 0, 65535));
      std::memcpy(dst, &c, 2);
      return;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const auto c = static_cast<int16_t>(integer(32767, -32768, 32767));
      std::memcpy(dst, &c, 2);
      return;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      const auto c = static_cast<uint32_t>(integer(4294967295.0, 0, 4294967295.0));
      std::memcpy(dst, &c, 4);
      return;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      const auto c = static_cast<int32_t>(integer(2147483647.0, -2147483648.0, 2147483647.0));
      std::memcpy(dst, &c, 4);
      return;
    }
  }
}

void updateMinMax(tinygltf::Model& model, int index) {
  const AccessorLayout l = accessorLayout(model, index, "", "");
  auto& acc = model.accessors[index];
  if (l.buffer < 0 || acc.count == 0) return;
  std::vector<double> lo(l.components, HUGE_VAL), hi(l.components, -HUGE_VAL);
  const unsigned char* data = model.buffers[l.buffer].data.data() + l.offset;
  for (size_t i = 0; i < acc.count; ++i)
    for (int k = 0; k < l.components; ++k) {
      const double c = loadComponent(data + i * l.stride + k * l.componentSize, acc.componentType);
      lo[k] = std::min(lo[k], c);
      hi[k] = std::max(hi[k], c);
    }
  acc.minValues = lo;
  acc.maxValues = hi;
}

}  // namespace geoshift::io
