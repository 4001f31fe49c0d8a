#include <sylva/core/output_check.hpp>

#include <sylva/core/atomic_file.hpp>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace sylva {
namespace {

namespace fs = std::filesystem;

Error io_error(const fs::path& path, const std::string& why) {
  return make_error(ErrorCode::kIo, fmt::format("{}: {}", path.string(), why));
}


// Creates and removes an empty file in `folder`; the error names `display`.
Status probe_folder(const fs::path& folder, const fs::path& display) {
  const fs::path probe = temp_path_beside(folder / ".sylva-write-check");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    return io_error(display, fmt::format("cannot create a file in the folder {} ({})", folder.string(), std::strerror(errno)));
  }
  ::close(fd);
  ::unlink(probe.c_str());
  return ok_status();
}

}  // namespace

Status check_output_file(const fs::path& path) {
  SYLVA_TRY(check_replaceable(path));
  return probe_folder(containing_folder(path), path);
}

Status check_output_image(const fs::path& path) {
  // The place first: a folder given as the screenshot has no extension, but "is a folder" is
  // what is wrong with it.
  SYLVA_TRY(check_output_file(path));
  // The writer is chosen by extension, as write_image() does; creating it opens no file.
  if (!OIIO::ImageOutput::create(path.string())) {
    OIIO::geterror();  // drop the message about the unknown format: ours names the path
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: no image format is known for the extension \"{}\" (use .png, .exr, .tif, .jpg)",
                                  path.string(), path.extension().string()));
  }
  return ok_status();
}

Status check_output_folder(const fs::path& folder) {
  std::error_code ec;
  fs::path existing = folder;
  while (!existing.empty() && !fs::exists(existing, ec)) existing = existing.has_parent_path() ? existing.parent_path() : fs::path();
  if (existing.empty()) existing = ".";
  if (!fs::is_directory(existing, ec)) {
    return io_error(folder, existing == folder ? "is a file, not a folder" : fmt::format("{} is not a folder", existing.string()));
  }
  return probe_folder(existing, folder);
}

Status check_not_an_input(const fs::path& output, std::span<const fs::path> inputs) {
  std::error_code ec;
  if (!fs::exists(output, ec)) return ok_status();
  for (const fs::path& input : inputs) {
    if (fs::equivalent(output, input, ec)) {
      return io_error(output, fmt::format("is an input of this run ({}); writing there would replace it", input.string()));
    }
  }
  return ok_status();
}

}  // namespace sylva
