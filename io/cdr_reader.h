// Reading of data serialized in OMG CDR as ROS 2 stores its messages (rosbag2's "cdr"
// serialization, XCDR1): a 4-byte encapsulation header (0x00, kind, two option bytes; kind 0 is
// big-endian CDR, 1 little-endian), then the fields in order, each primitive aligned to its own
// size counted from the end of the header; a string is a uint32 length that counts its
// terminating NUL, then the bytes; a sequence a uint32 count, then its elements; a fixed array
// its elements only. Every read is checked against the bytes there are.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace slipgraph {

// Bytes that are not CDR or end before the field being read.
class CdrError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CdrReader {
 public:
  // Reads the encapsulation header. Throws CdrError when it is not plain CDR.
  CdrReader(const uint8_t* data, size_t size);

  uint8_t U8();
  int8_t I8() { return static_cast<int8_t>(U8()); }
  uint16_t U16();
  int32_t I32() { return static_cast<int32_t>(U32()); }
  uint32_t U32();
  double F64();
  std::string String();
  // A sequence's element count, checked against the bytes left at `min_element_bytes` each.
  uint32_t SequenceLength(size_t min_element_bytes);
  // `n` doubles of a fixed array or a sequence.
  void Doubles(double* out, size_t n);

 private:
  void Align(size_t bytes);
  const uint8_t* Take(size_t bytes);  // aligned already; throws when fewer are left

  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 4;  // past the encapsulation header
  bool swap_ = false;  // the data's byte order is not the machine's
};

}  // namespace slipgraph
