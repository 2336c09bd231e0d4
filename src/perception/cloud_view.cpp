#include "offshore_gnc/perception/cloud_view.h"

#include <sstream>

namespace offshore_gnc {
namespace perception {

const char* toString(CloudError e) {
  switch (e) {
    case CloudError::None: return "ok";
    case CloudError::Empty: return "empty_cloud";
    case CloudError::MissingXyz: return "missing_xyz";
    case CloudError::BadFieldType: return "bad_field";
    case CloudError::SizeMismatch: return "size_mismatch";
    case CloudError::BigEndian: return "big_endian";
  }
  return "unknown";
}

std::size_t typeSize(std::uint8_t t) {
  switch (static_cast<FieldType>(t)) {
    case FieldType::Int8: case FieldType::UInt8: return 1;
    case FieldType::Int16: case FieldType::UInt16: return 2;
    case FieldType::Int32: case FieldType::UInt32: case FieldType::Float32: return 4;
    case FieldType::Float64: return 8;
  }
  return 0;
}

double readField(const std::uint8_t* p, std::uint8_t t) {
  switch (static_cast<FieldType>(t)) {
    case FieldType::Int8: return loadUnaligned<std::int8_t>(p);
    case FieldType::UInt8: return loadUnaligned<std::uint8_t>(p);
    case FieldType::Int16: return loadUnaligned<std::int16_t>(p);
    case FieldType::UInt16: return loadUnaligned<std::uint16_t>(p);
    case FieldType::Int32: return loadUnaligned<std::int32_t>(p);
    case FieldType::UInt32: return loadUnaligned<std::uint32_t>(p);
    case FieldType::Float32: return loadUnaligned<float>(p);
    case FieldType::Float64: return loadUnaligned<double>(p);
  }
  return 0.0;
}

CloudError checkCloudLayout(const CloudView& c, std::string& message) {
  std::ostringstream os;
  auto fail = [&](CloudError e) {
    message = os.str();
    return e;
  };
  if (c.width == 0 || c.height == 0 || c.size == 0) {
    os << "empty cloud (" << c.width << " x " << c.height << ", " << c.size << " bytes)";
    return fail(CloudError::Empty);
  }
  if (!c.x.present || !c.y.present || !c.z.present) {
    os << "cloud lacks an x, y or z field";
    return fail(CloudError::MissingXyz);
  }
  if (c.big_endian) {
    os << "big-endian clouds are not supported";
    return fail(CloudError::BigEndian);
  }
  for (const CloudField* f : {&c.x, &c.y, &c.z}) {
    const auto t = static_cast<FieldType>(f->datatype);
    if (t != FieldType::Float32 && t != FieldType::Float64) {
      os << "x/y/z must be FLOAT32 or FLOAT64, got datatype " << int(f->datatype);
      return fail(CloudError::BadFieldType);
    }
    if (f->offset + typeSize(f->datatype) > c.point_step) {
      os << "field at offset " << f->offset << " does not fit in point_step " << c.point_step;
      return fail(CloudError::BadFieldType);
    }
  }
  const std::uint64_t min_row = std::uint64_t(c.width) * c.point_step;
  if (c.row_step < min_row || std::uint64_t(c.row_step) * c.height != c.size) {
    os << "data size " << c.size << " disagrees with " << c.width << " x " << c.height << " points, point_step "
       << c.point_step << ", row_step " << c.row_step;
    return fail(CloudError::SizeMismatch);
  }
  message.clear();
  return CloudError::None;
}

}  // namespace perception
}  // namespace offshore_gnc
