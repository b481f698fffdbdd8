#pragma once
// The viewer's page and three.js, built into hapticctl
// (cmake/embed_web_assets.cmake): `hapticctl view` serves them with
// nothing to find or download at run time.

#include <span>
#include <string_view>

namespace hs::cli {

struct WebAsset {
  /// The URL path it is served at, e.g. "/index.html", "/vendor/three.module.js".
  std::string_view path;
  std::string_view content_type;
  std::string_view body;
};

/// Every asset, in no particular order.
std::span<const WebAsset> WebAssets();

}  // namespace hs::cli
