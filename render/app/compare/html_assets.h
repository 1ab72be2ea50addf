#pragma once
// The report page's stylesheet and script, inlined into report.html.
namespace spume::compare {

extern const char* const kReportCss;
// Reads the frame data from <script id="compare-data" type="application/json">, drives the viewer,
// sorting, filtering and plot clicks. Sets <body data-status> to "ready" when set up, or "error" (and
// shows #script-error) when anything throws, so a browser test can tell.
extern const char* const kReportJs;

}  // namespace spume::compare
