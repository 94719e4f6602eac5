#pragma once
// Reading the small text files a user hands to adjoin (scenes, sweeps, target tables), and
// quoting their bytes in messages.
//
// read_text_file refuses, with a message that starts with the file's name and says what was
// expected, every input that is not a readable UTF-8 text file: a missing file, a folder, a
// FIFO, device or socket (never opened, so the program cannot block on it), a file larger
// than `max_bytes`, UTF-16/UTF-32 text (by its byte-order mark), a NUL byte, and bytes that
// are not UTF-8 (binary garbage), each with its line and a short escaped excerpt. A UTF-8
// byte-order mark is dropped.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "adjoin/core/number_text.hpp"  // (number_text, for io's messages)

namespace adjoin {

// `what` names the kind of file in messages ("scene", "sweep").
std::string read_text_file(const std::filesystem::path& file, const std::string& what,
                           std::size_t max_bytes = std::size_t{16} << 20);

// The bytes of `text` as printable text: at most `max_chars` characters (then "..."), with
// control characters, DEL and bytes that are not valid UTF-8 written as \xNN, and quotes
// and backslashes escaped. For quoting user input in messages.
std::string escaped_excerpt(std::string_view text, std::size_t max_chars = 40);

// A key, option or --set as the user wrote it, for messages: the text itself when it is at
// most 80 characters of printable text (solver.h=0.01), else its escaped_excerpt.
std::string text_excerpt(std::string_view text);

// A message made safe to print: valid UTF-8 sequences, newlines and tabs kept; other control
// characters and invalid bytes written as \xNN.
std::string printable_message(std::string_view message);

}  // namespace adjoin
