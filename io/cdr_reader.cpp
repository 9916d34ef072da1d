#include "io/cdr_reader.h"

#include <algorithm>
#include <cstring>

namespace slipgraph {
namespace {

bool MachineIsLittleEndian() {
  const uint16_t one = 1;
  uint8_t first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

template <typename T>
T FromBytes(const uint8_t* bytes, bool swap) {
  uint8_t copy[sizeof(T)];
  std::memcpy(copy, bytes, sizeof(T));
  if (swap) std::reverse(copy, copy + sizeof(T));
  T value;
  std::memcpy(&value, copy, sizeof(T));
  return value;
}

}  // namespace

CdrReader::CdrReader(const uint8_t* data, size_t size) : data_(data), size_(size) {
  if (size < 4) throw CdrError("shorter than the CDR encapsulation header");
  if (data[0] != 0 || data[1] > 1) {
    throw CdrError("not plain CDR (encapsulation " + std::to_string(data[0]) + ", " +
                   std::to_string(data[1]) + ")");
  }
  const bool little = data[1] == 1;
  swap_ = little != MachineIsLittleEndian();
}

void CdrReader::Align(size_t bytes) {
  const size_t position = offset_ - 4;
  offset_ += (bytes - position % bytes) % bytes;
}

const uint8_t* CdrReader::Take(size_t bytes) {
  if (offset_ > size_ || size_ - offset_ < bytes) {
    throw CdrError("message ends at byte " + std::to_string(size_) + ", a field needs " +
                   std::to_string(bytes) + " from byte " + std::to_string(offset_));
  }
  const uint8_t* out = data_ + offset_;
  offset_ += bytes;
  return out;
}

uint8_t CdrReader::U8() { return *Take(1); }

uint16_t CdrReader::U16() {
  Align(2);
  return FromBytes<uint16_t>(Take(2), swap_);
}

uint32_t CdrReader::U32() {
  Align(4);
  return FromBytes<uint32_t>(Take(4), swap_);
}

double CdrReader::F64() {
  Align(8);
  return FromBytes<double>(Take(8), swap_);
}

std::string CdrReader::String() {
  const uint32_t length = U32();
  if (length == 0) return std::string();  // some writers leave out the NUL of an empty string
  const uint8_t* bytes = Take(length);
  return std::string(reinterpret_cast<const char*>(bytes), length - 1);
}

uint32_t CdrReader::SequenceLength(size_t min_element_bytes) {
  const uint32_t n = U32();
  const size_t left = size_ > offset_ ? size_ - offset_ : 0;
  if (min_element_bytes > 0 && n > left / min_element_bytes) {
    throw CdrError("a sequence of " + std::to_string(n) + " elements in " + std::to_string(left) +
                   " bytes");
  }
  return n;
}

void CdrReader::Doubles(double* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = F64();
}

}  // namespace slipgraph
