#include "harness/image/exr_header.h"

#include <fstream>
#include <string>

namespace xshade::harness {
namespace {

// OpenEXR's layout ("OpenEXR File Layout", openexr.com): the magic number, a version word whose
// flags say whether names may be long and whether the file has several parts, then each part's
// header, a list of attributes (name, type name, size, value) ended by an empty name; a
// multi-part file ends its list of headers with an empty header.
constexpr uint32_t kMagic = 20000630;
constexpr uint32_t kMultiPartFlag = 0x1000;

class HeaderReader {
 public:
  HeaderReader(std::ifstream& file, uint64_t size) : file_(file), size_(size) {}

  // A name or type name, up to its NUL; nullopt where the header is too broken to go on.
  std::optional<std::string> text(size_t longest) {
    std::string out;
    for (char c; file_.get(c);) {
      if (c == '\0') return out;
      if (out.size() == longest) return std::nullopt;
      out += c;
    }
    return std::nullopt;
  }
  std::optional<int32_t> int32() {
    unsigned char bytes[4];
    if (!file_.read(reinterpret_cast<char*>(bytes), 4)) return std::nullopt;
    return int32_t(uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 | uint32_t(bytes[3]) << 24);
  }
  uint64_t remaining() { return size_ - uint64_t(file_.tellg()); }
  void skip(int32_t bytes) { file_.seekg(bytes, std::ios::cur); }

 private:
  std::ifstream& file_;
  uint64_t size_;
};

}  // namespace

Result<std::optional<ExrDataWindow>> exr_data_window(const std::filesystem::path& path) {
  std::error_code error;
  const uint64_t size = std::filesystem::file_size(path, error);
  std::ifstream file(path, std::ios::binary);
  if (error || !file) return std::nullopt;  // OpenImageIO says why it cannot open it
  HeaderReader header(file, size);
  const std::optional<int32_t> magic = header.int32(), version = header.int32();
  if (!magic || uint32_t(*magic) != kMagic || !version) return std::nullopt;
  // A name of up to 255 bytes whatever the long-names flag says: OpenEXR reads one so, and the
  // walk must not stop where OpenEXR goes on (a fuzzed 100-byte name before a data window of 7.8
  // million pixels a line took 35 s and gigabytes under AddressSanitizer).
  const size_t longest_name = 255;
  const bool multi_part = (uint32_t(*version) & kMultiPartFlag) != 0;
  std::optional<ExrDataWindow> window;
  for (bool first = true;; first = false) {
    size_t attributes = 0;
    for (;; ++attributes) {
      const std::optional<std::string> name = header.text(longest_name);
      if (!name) return window;  // broken past here: OpenImageIO says how, once the window is held
      if (name->empty()) break;  // the end of this header
      const std::optional<std::string> type = header.text(longest_name);
      const std::optional<int32_t> bytes = header.int32();
      if (!type || !bytes) return window;
      if (*bytes < 0 || uint64_t(*bytes) > header.remaining())
        return fail(ErrorKind::UserInput, "cannot read image " + path.string() + ": its header's attribute '" + *name +
                                              "' claims " + std::to_string(*bytes) +
                                              " bytes, more than the file holds (" + std::to_string(size) +
                                              " bytes in all)");
      if (*name == "dataWindow" && *type == "box2i" && *bytes == 16 && !window) {
        const std::optional<int32_t> x_min = header.int32(), y_min = header.int32(), x_max = header.int32(),
                                     y_max = header.int32();
        if (!x_min || !y_min || !x_max || !y_max) return std::nullopt;
        window = ExrDataWindow{int64_t(*x_max) - *x_min + 1, int64_t(*y_max) - *y_min + 1};
        continue;
      }
      header.skip(*bytes);
    }
    // One header, or a multi-part file's list of them, ended by an empty one.
    if (!multi_part || (attributes == 0 && !first)) return window;
  }
}

}  // namespace xshade::harness
