#include "bench/bench_embree_scene.h"

#include <array>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/kinds/polygon.h"

namespace quiver::bench {

namespace {

void report_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree error %d: %s\n", int(code), message ? message : "");
}

void check(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) throw std::runtime_error(std::string("embree: ") + what + " failed");
}

}  // namespace

EmbreeDevice::EmbreeDevice(const std::string& max_isa)
    : device_(rtcNewDevice(max_isa.empty() ? nullptr : ("max_isa=" + max_isa).c_str())) {
  if (!device_) throw std::runtime_error("embree: rtcNewDevice failed (max_isa '" + max_isa + "')");
  rtcSetDeviceErrorFunction(device_, report_error, nullptr);
  rtcSetDeviceMemoryMonitorFunction(device_, monitor, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

bool EmbreeDevice::native_packets(int width) const {
  switch (width) {
    case 4: return rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED) != 0;
    case 8: return rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0;
    case 16: return rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
    default: throw std::invalid_argument("embree: no ray packets of width " + std::to_string(width));
  }
}

bool EmbreeDevice::monitor(void* user, ssize_t bytes, bool) {
  static_cast<EmbreeDevice*>(user)->bytes_ += std::int64_t(bytes);  // negative on release
  return true;
}

EmbreeScene build_embree_scene(const EmbreeDevice& device, const SceneDesc& desc, const Scene& scene, bool robust,
                               RTCBuildQuality quality) {
  EmbreeScene out;
  const RTCDevice d = device.get();
  const std::int64_t before = device.monitored_bytes();
  const auto start = std::chrono::steady_clock::now();

  std::vector<std::array<float, 4>> spheres;  // x, y, z, r
  std::vector<Vec3<float>> vertices;          // 3 per triangle
  for (const GeometryLayer* layer : {&scene.opaque, &scene.transmissive}) {
    for (std::size_t i = 0; i < layer->store<SphereKind>().count; ++i) {
      const SphereDesc& s = desc.spheres[layer->origins<SphereKind>()[i].index].sphere;
      spheres.push_back({s.center.x, s.center.y, s.center.z, s.radius});
    }
    for (std::size_t i = 0; i < layer->store<TriangleKind>().count; ++i) {
      for (int k = 0; k < 3; ++k) vertices.push_back(layer->store<TriangleKind>().vertex(i, k));
    }
    for (std::size_t i = 0; i < layer->store<PolygonKind>().count; ++i) {
      const PolygonDesc& polygon = desc.polygons[layer->origins<PolygonKind>()[i].index].polygon;
      for (const auto& triangle : triangulate_polygon(polygon)) {
        for (const Vec3<float>& p : triangle) vertices.push_back(p);
      }
      ++out.polygons_triangulated;
    }
    out.skipped_planes += layer->store<PlaneKind>().count;
    out.skipped_cones += layer->store<ConeKind>().count;
  }

  out.scene.reset(rtcNewScene(d));
  const RTCScene built = out.scene.get();
  if (robust) rtcSetSceneFlags(built, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(built, quality);
  if (!spheres.empty()) {
    const RTCGeometry g = rtcNewGeometry(d, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* buffer = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size()));
    check(d, "sphere buffer");
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      for (int k = 0; k < 4; ++k) buffer[4 * i + k] = spheres[i][k];
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(built, g);
    rtcReleaseGeometry(g);
    out.spheres = spheres.size();
    out.buffer_bytes += spheres.size() * 4 * sizeof(float);
  }
  if (!vertices.empty()) {
    const std::size_t count = vertices.size() / 3;
    const RTCGeometry g = rtcNewGeometry(d, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
    auto* index = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), count));
    check(d, "triangle buffers");
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      v[3 * i] = vertices[i].x;
      v[3 * i + 1] = vertices[i].y;
      v[3 * i + 2] = vertices[i].z;
      index[i] = static_cast<std::uint32_t>(i);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(built, g);
    rtcReleaseGeometry(g);
    out.triangles = count;
    out.buffer_bytes += vertices.size() * 3 * sizeof(float) + count * 3 * sizeof(std::uint32_t);
  }
  const auto commit_start = std::chrono::steady_clock::now();
  rtcCommitScene(built);
  const auto end = std::chrono::steady_clock::now();
  check(d, "rtcCommitScene");
  out.build_ms = std::chrono::duration<double, std::milli>(end - start).count();
  out.commit_ms = std::chrono::duration<double, std::milli>(end - commit_start).count();
  out.monitored_bytes = device.monitored_bytes() - before;
  return out;
}

}  // namespace quiver::bench
