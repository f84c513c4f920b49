#include "io/text_file.h"

#include <cstdint>
#include <fstream>
#include <system_error>

#include "io/parse_error.h"

namespace quiver {

std::string read_text_file(const std::filesystem::path& path, std::size_t max_bytes, std::string_view what,
                           std::string_view bound_reason) {
  const std::string name = path.string();
  auto fail = [&](std::string_view problem) {
    std::string message = "cannot read ";
    message += what;
    message += ": ";
    message += problem;
    throw ParseError::whole_file(name, message);
  };
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) fail("no such file");
  if (std::filesystem::is_directory(status)) fail("it is a directory");
  // A FIFO, socket or device could block or never end.
  if (!std::filesystem::is_regular_file(status)) fail("not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot open it");
  auto too_large = [&] {
    std::string message = "larger than the limit of " + std::to_string(max_bytes) + " bytes";
    if (!bound_reason.empty()) message += " (" + std::string(bound_reason) + ")";
    fail(message);
  };
  std::string text;
  // Sized once from the file's size (doubling would hold up to twice the
  // text); the bound is checked again while reading, as the file may grow.
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > max_bytes) too_large();
  if (!error) text.reserve(static_cast<std::size_t>(size));
  std::string chunk(std::size_t{1} << 16, '\0');
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got > max_bytes - text.size()) too_large();
    text.append(chunk.data(), got);
  }
  if (in.bad()) fail("read error");
  return text;
}

}  // namespace quiver
