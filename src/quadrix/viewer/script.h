// The viewer's commands and scripted input (issue 18 §2, §7).
//
// Commands are what keys do: a table from key names (SDL_GetKeyName's spelling, compared without
// case) to commands, shared by the window and the script's `key` line, so that a script presses
// the very keys a user does:
//   1 front  2 back  3 left  4 right  5 top  6 bottom  0 or I isometric
//   P perspective/parallel   L show-edges on/off   R reset   F fit all   V print the view   E /
//   shift-E next/previous engine   S screenshot   H help   Q or Escape quit
//   X section plane on/off (shift-X: keep the other side)   [ and ] move it away from / toward
//   the viewer (ctrl-left-drag too)   C hatching of its cut faces on/off (on at the start)
//   O overlay on/off   D write the view as an SVG drawing
//
// A script (`quadrix view --script FILE`) is a text file of events, one a line, `#` to the end of
// a line is a comment. Positions and motions are in window pixels.
//   orbit DX DY [STEPS]   a left-button drag by (DX, DY) from the window's centre, in STEPS
//                         motion events (default 1)
//   pan DX DY [STEPS]     the same with the right button
//   zoom CLICKS [X Y]     mouse-wheel clicks (> 0 zooms in) at (X, Y), default the centre
//   click X Y             wait, then a left click without motion: a pick (the script goes on
//                         once it is answered)
//   click-now X Y         the same without waiting for the full-resolution frame (a pick while
//                         a frame is being drawn)
//   key NAME              a key press, e.g. `key 5`, `key P`, `key Escape`
//   engine NAME           switch to a registered engine (or `next`)
//   wait                  until the full-resolution frame of the current view is shown
//   screenshot FILE       wait, then save the window's picture (PNG or PNM by extension),
//                         the frame without the overlay
//   screenshot-window FILE  the same with what the window shows over it (the overlay)
//   section-drag DY [STEPS]  a ctrl-left-drag by DY pixels: moves the section plane
//   drawing FILE          wait, then write the view's hidden-line drawing (.svg, .pdf, .eps)
//   print-view [FILE]     print the view statement (standard output, or written to FILE)
//   sleep MS              let MS milliseconds of real time pass (file reloads, progressive frames)
//   wait-reload           until the input files have changed and been read again (successfully
//                         or not); more than 20 s is an error
//   quit                  close the window (the end of the script does too)
// Errors are reported at file:line:column; a bad script opens no window.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/source_loc.h"

namespace quadrix::viewer {

enum class Command {
    kNone,
    kFront,
    kBack,
    kLeft,
    kRight,
    kTop,
    kBottom,
    kIso,
    kTogglePerspective,
    kToggleEdges,
    kReset,
    kFitAll,
    kPrintView,
    kNextEngine,
    kPreviousEngine,
    kScreenshot,
    kHelp,
    kQuit,
    kToggleSection,
    kFlipSection,
    kSectionAway,    // [ : the plane moves away from the viewer it was made for (cuts more)
    kSectionToward,  // ]
    kToggleOverlay,
    kToggleHatch,
    kDrawing,
};

// The command of a key (kNone for keys that do nothing).
Command CommandForKey(std::string_view keyName, bool shift);
// One help line per key, for `H` and docs/viewer.md.
std::string KeyHelp();

struct ScriptEvent {
    enum class Kind {
        kOrbit,
        kPan,
        kZoom,
        kClick,
        kClickNow,
        kKey,
        kEngine,
        kWait,
        kScreenshot,
        kScreenshotWindow,
        kSectionDrag,
        kDrawing,
        kPrintView,
        kSleep,
        kWaitReload,
        kQuit
    };
    Kind kind = Kind::kWait;
    double x = 0, y = 0;  // orbit/pan/section-drag: motion; zoom/click: position (NaN = centre)
    double amount = 0;    // zoom: clicks; sleep: milliseconds
    int steps = 1;        // orbit/pan
    std::string text;     // key name, engine name, file name
    SourceLoc loc;
};

// Parses a script; nullopt with errors (file:line:column) in diags.
std::optional<std::vector<ScriptEvent>> ParseScript(std::string_view text, const std::string& name,
                                                    Diagnostics& diags);

}  // namespace quadrix::viewer
