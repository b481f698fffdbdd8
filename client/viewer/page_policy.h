#pragma once
// The headers the viewer bridge sends with everything it serves: a
// Content-Security-Policy that lets the page load, run and connect to
// nothing but the bridge itself (so text from the server that reached
// the page as markup could not run, and no other site can frame it), no
// content-type sniffing, and no Referer (the page's address carries the
// bridge's secret until the page drops it).

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hs::cli {

/// 'sha256-BASE64' of the text of each inline <script> (one without a
/// src) in `html`, in order: the page's import map is one.
std::vector<std::string> InlineScriptHashes(std::string_view html);

/// The Content-Security-Policy for a page whose HTML is `index_html`:
/// default-src 'self', its inline scripts by their hashes, connections to
/// its own origin (CSP Level 3's 'self' covers ws:// and wss:// there),
/// data: images (the favicon, a snapshot's frozen canvas), and no framing,
/// plugins, <base> or forms.
std::string PageContentSecurityPolicy(std::string_view index_html);

/// Every header above as (name, value) pairs.
std::vector<std::pair<std::string, std::string>> PageSecurityHeaders(std::string_view index_html);

}  // namespace hs::cli
