#pragma once
// Text into HTML: escaping for element content and attributes, and file paths as relative URLs.
#include <filesystem>
#include <string>

namespace spume::compare {

std::string html_escape(const std::string& text);  // & < > " '

// `target` relative to the folder `from`, as a URL path: every byte but unreserved ones and '/'
// percent-encoded, so names with spaces, '#' or '%' load as files.
std::string relative_url(const std::filesystem::path& target, const std::filesystem::path& from);

// A relative path already in the output folder (thumbs/x.png) as a URL.
std::string url_path(const std::string& relative);

}  // namespace spume::compare
