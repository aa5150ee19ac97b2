#pragma once
// The picture viewer of loom-compare's HTML report: click a case's picture and it opens over the
// page, where the pictures of the case lie on top of each other, pixel for pixel; keys or buttons
// show one of them, flip between the backends (or blink), zoom in whole steps with each pixel a
// sharp square (CSS image-rendering: pixelated) and name the pixel under the pointer. Inline
// style, markup and script: the report needs no network and no other file than its pictures.
//
// The report marks each case's pictures for it: <div class="pictures" data-case="ID"
// data-title="..."> holding <figure data-image="KEY" data-label="..." [data-backend]><a><img
// src="..."></a></figure>. The address opens the viewer too (report.html#view=ID&image=KEY&zoom=4,
// zoom a step or "fit"), and the viewer keeps it current, so that a link shows what one sees. The
// viewer writes data-case, data-image and data-zoom on #viewer, and the page data-status ("ok" or
// "error") and data-errors on <body> once its script ran (the headless browser test reads them).

namespace loom::compare::viewer {

/// Rules for the viewer, inside the report's <style>.
extern const char* const kStyle;
/// Collects the page's errors before any other script runs: the first thing in <head>.
extern const char* const kErrorCollector;
/// The viewer's markup and script: the last thing in <body>.
extern const char* const kBody;

}  // namespace loom::compare::viewer
