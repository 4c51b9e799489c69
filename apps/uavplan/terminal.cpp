// Everything the tool prints goes through a filter that writes control characters as escapes
// (\x1b, \r, \x07, C1 controls): a UAV id, a scenario name or a message that came from a file
// cannot clear the screen, set the window title or forge a line ("status: solved" after a \r).
// The filter sits under stdout / stderr (printf) and std::cout / std::cerr alike, so no print
// call can forget it; newlines and tabs pass. Progress lines write their own \r and clear-line
// to the terminal's descriptor directly (progress.cpp).
#include <cstdio>
#include <cstring>
#include <iostream>
#include <streambuf>

#include "commands.h"

namespace uavplan::cli {
namespace {

struct FilterState {
  std::FILE* to = nullptr;  // the stream the filtered bytes go to
  bool after_c2 = false;    // the last byte was 0xC2, the lead byte of U+0080..U+00BF
};

void put_escape(std::FILE* to, unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02x", c);
  std::fputs(buf, to);
}

// Writes n bytes with C0 controls (but \n and \t), DEL and C1 controls (U+0080..U+009F, as
// UTF-8 C2 80..C2 9F) escaped.
void filter(FilterState& s, const char* data, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k) {
    const auto c = static_cast<unsigned char>(data[k]);
    if (s.after_c2) {
      s.after_c2 = false;
      if (c >= 0x80 && c <= 0x9f) {
        std::fputs("\\u00", s.to);
        char buf[4];
        std::snprintf(buf, sizeof buf, "%02x", c);
        std::fputs(buf, s.to);
        continue;
      }
      std::fputc(0xc2, s.to);
    }
    if (c == 0xc2) {
      s.after_c2 = true;
    } else if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      put_escape(s.to, c);
    } else {
      std::fputc(c, s.to);
    }
  }
}

ssize_t cookie_write(void* cookie, const char* data, std::size_t n) {
  filter(*static_cast<FilterState*>(cookie), data, n);
  return static_cast<ssize_t>(n);
}

int cookie_close(void* cookie) {
  auto* s = static_cast<FilterState*>(cookie);
  if (s->after_c2) std::fputc(0xc2, s->to);
  s->after_c2 = false;
  return std::fflush(s->to);
}

// std::cout / std::cerr onto the filtered FILE, so C++ and C output keep their order.
class FileBuf final : public std::streambuf {
 public:
  explicit FileBuf(std::FILE* f) : f_(f) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    return std::fputc(c, f_) == EOF ? traits_type::eof() : c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    return static_cast<std::streamsize>(std::fwrite(s, 1, static_cast<std::size_t>(n), f_));
  }
  int sync() override { return std::fflush(f_); }

 private:
  std::FILE* f_;
};

std::FILE* filtered(std::FILE* to, FilterState& state) {
  state.to = to;
  cookie_io_functions_t io{};
  io.write = cookie_write;
  io.close = cookie_close;
  std::FILE* f = ::fopencookie(&state, "w", io);
  if (f) std::setvbuf(f, nullptr, _IONBF, 0);  // the stream below keeps its own buffering
  return f ? f : to;
}

}  // namespace

void install_terminal_filter() {
  static FilterState out_state, err_state;
  std::cout.flush();
  std::cerr.flush();
  std::FILE* out = filtered(stdout, out_state);
  std::FILE* err = filtered(stderr, err_state);
  static FileBuf out_buf(out), err_buf(err);
  stdout = out;
  stderr = err;
  std::cout.rdbuf(&out_buf);
  std::cerr.rdbuf(&err_buf);
}

}  // namespace uavplan::cli
