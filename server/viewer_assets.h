// The web viewer's files (server/viewer/: HTML, CSS, JavaScript), embedded
// into scallopd at build time by cmake/EmbedFiles.cmake, so the binary
// serves them with no files beside it and no build step for the page.
#pragma once

#include <string_view>

namespace scallop::server {

struct ViewerAsset {
  std::string_view path;          // "/index.html", "/viewer.js"
  std::string_view content_type;  // from the extension
  std::string_view bytes;
  std::string_view etag;  // quoted digest of the bytes
};

// The file served at `path` ("/" is "/index.html"), or null. O(files).
const ViewerAsset* FindViewerAsset(std::string_view path);

}  // namespace scallop::server
