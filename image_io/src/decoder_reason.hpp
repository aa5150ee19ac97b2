#pragma once
// The image decoder's (stb_image's) reason for its latest failure, made printable.

#include <string>

namespace loom::image_io::detail {

/// stb_image's failure reason with every byte outside printable ASCII written as \xNN. For an
/// unknown critical PNG chunk stb_image puts the chunk's four type bytes, taken from the file,
/// into the reason ("XXXX PNG chunk not known"), so a file could otherwise put a newline (or
/// any byte) into a one-line error.
std::string decoder_reason();

}  // namespace loom::image_io::detail
