#pragma once
// The PLY container (header and records, ascii and binary of either byte order), shared by the mesh
// reader (ply.cpp) and the terrain point reader (terrain_ply.cpp). The header is checked against
// the file before anything is allocated: every element's records need at least a known number of
// bytes, so counts the data cannot hold are refused at once.
#include <cstdint>
#include <string>
#include <vector>

namespace geoshift::io::ply {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };
enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

size_t sizeOf(Type t);
bool isInteger(Type t);
const char* typeName(Type t);

struct Property {
  std::string name;
  Type type = Type::F32;
  bool list = false;
  Type countType = Type::U8;
};

struct Element {
  std::string name;
  // 64 bits in every build: a declared count must not wrap in wasm32's 32-bit size_t before it is
  // checked against the file's size.
  std::uint64_t count = 0;
  std::vector<Property> props;
  int find(const std::string& property) const;  // index or -1
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  size_t bodyStart = 0;  // byte offset of the first record
  size_t bodyLine = 0;   // line number of the first record (ascii messages)
  int findElement(const std::string& name) const;
};

// Throws InputError "PATH: header line N: ..." on a malformed header or unknown type, and
// "PATH: element 'E' declares N records, more than the remaining D bytes can hold" when the counts
// cannot fit in the file (binary: fixed bytes per record; ascii: two bytes per value).
Header parseHeader(const std::string& path, const std::string& bytes);

// Reads the records in file order. Messages name the file, the element and record index, and for
// ascii files the line: "PATH:LINE: vertex 3: ...".
class Records {
 public:
  Records(const std::string& path, const std::string& bytes, const Header& header);

  // Starts record `index` of `element` (ascii: moves to its line and splits it into values).
  void begin(const Element& element, size_t index);
  // Checks that an ascii record had no values left over.
  void end();
  double scalar(const Property& p);
  // A list's length; bounded by the bytes left in the file (binary) or values left on the line.
  size_t listLength(const Property& p);
  double listItem(const Property& p);
  // Skips one property (scalar or the whole list).
  void skip(const Property& p);

  // "PATH:LINE: vertex 3" / "PATH: vertex 3" followed by ": what".
  [[noreturn]] void fail(const std::string& what) const;
  // Bytes or non-blank text left after the last element (a warning for the caller).
  bool trailingData() const;

 private:
  // `what` and `name` describe the value for a message ("property" 'x'): composed only on failure,
  // since a mesh has millions of values.
  double binary(Type t, const char* what, const std::string& name);
  double text(Type t, const char* what, const std::string& name);

  const std::string& path_;
  const std::string& b_;
  Encoding encoding_;
  size_t pos_ = 0;
  size_t line_ = 0;  // ascii: current line number
  const Element* element_ = nullptr;  // the record being read, for messages
  size_t index_ = 0;
  // ascii: the current record's values as [begin, end) offsets into b_
  std::vector<std::pair<size_t, size_t>> tokens_;
  size_t next_ = 0;
};

}  // namespace geoshift::io::ply
