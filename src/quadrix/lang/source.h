// One input of the reader: the text of a file, a string or standard input, with a line index for
// diagnostics (built when the first diagnostic needs it).
//
// A Source may be complete from the start (files, ReadText) or grow a line at a time (standard
// input), so that an interactive session can execute a statement as soon as its ';' is typed:
// the lexer asks for more text only when it needs a character it does not have yet.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace quadrix::lang {

class Source {
  public:
    // Appends the next line (including its '\n' when there is one) to `text`; false at end of
    // input.
    using LineReader = std::function<bool(std::string& text)>;

    Source(std::string name, std::string text);
    Source(std::string name, LineReader readLine);

    // Pushed text (an interactive session's Feed): appends to a source built from text. A
    // parser that reached the end of the text may go on once more is appended
    // (Parser::RunAvailable).
    void Append(std::string_view more);
    std::size_t Size() const { return text_.size(); }

    // The name used in diagnostics; shared by every SourceLoc of this source.
    const std::shared_ptr<const std::string>& Name() const { return name_; }

    // True when byte `pos` exists, reading more lines when needed. Inline for the bytes already
    // held (the lexer asks once per byte); only the growing case leaves the header.
    bool Has(std::size_t pos) { return pos < text_.size() || ReadMore(pos); }
    // Byte `pos`; only valid after Has(pos) returned true.
    char At(std::size_t pos) const { return text_[pos]; }
    // The bytes held from `pos` on (valid until the source grows); `pos` <= Size().
    std::string_view From(std::size_t pos) const { return std::string_view(text_).substr(pos); }

    // The text of 1-based line `line` for a diagnostic: without its newline, control characters
    // replaced by '?', and shortened when very long (the caret must still point at `column`, so
    // lines are cut after the column, never before; a column beyond kMaxShownColumn shows no
    // line at all). Empty when unknown.
    std::string LineForDiagnostic(int line, int column) const;

    static constexpr int kMaxShownColumn = 1000;

  private:
    bool ReadMore(std::size_t pos);
    // Extends lineStarts_ over the text held now. Lines are indexed only when a diagnostic
    // shows one (the lexer counts lines itself): most inputs never need the index.
    void IndexLines() const;

    std::shared_ptr<const std::string> name_;
    std::string text_;
    mutable std::vector<std::size_t> lineStarts_{0};  // offset of the first byte of each line
    mutable std::size_t indexedTo_ = 0;               // bytes searched for line starts so far
    LineReader readLine_;                             // empty when the text is complete
};

}  // namespace quadrix::lang
