#pragma once
// A PointCloud2-layout buffer read in place, ROS-free: its fields, the layout checks every reader makes, and the
// field reads. Shared by the LiDAR targets (a frame) and the wall detection (a sonar sweep).
#include <cstdint>
#include <cstring>
#include <string>

namespace offshore_gnc {
namespace perception {

// sensor_msgs/PointField datatype codes (a wire format, so the core can read the buffer without ROS).
enum class FieldType : std::uint8_t { Int8 = 1, UInt8 = 2, Int16 = 3, UInt16 = 4, Int32 = 5, UInt32 = 6, Float32 = 7, Float64 = 8 };

struct CloudField {
  bool present = false;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;  // FieldType code as received (validated by checkCloudLayout)
  std::uint32_t count = 1;
};

// A view of a PointCloud2's buffer: nothing is copied.
struct CloudView {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::uint32_t width = 0, height = 0, point_step = 0, row_step = 0;
  bool big_endian = false;
  CloudField x, y, z, ring;
};

enum class CloudError { None, Empty, MissingXyz, BadFieldType, SizeMismatch, BigEndian };
const char* toString(CloudError e);  // also the name of its counter

// The layout alone, O(1): no points, no x/y/z, big-endian, x/y/z not FLOAT32/FLOAT64 or outside point_step, a
// buffer whose size disagrees with width x height. None when the points can be read; otherwise the reason in
// `message`.
CloudError checkCloudLayout(const CloudView& c, std::string& message);

std::size_t typeSize(std::uint8_t datatype);  // 0 for an unknown code

template <typename T>
T loadUnaligned(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));  // PointCloud2 offsets need not be aligned
  return v;
}

// A field's value at `p` as a double (0 for an unknown code).
double readField(const std::uint8_t* p, std::uint8_t datatype);

}  // namespace perception
}  // namespace offshore_gnc
