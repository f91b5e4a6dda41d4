// x11-window-tool: what tests/test_visualizer.sh needs of an X display, with Xlib alone.
//   x11-window-tool wait-window NAME SECONDS      waits for a mapped window whose name contains NAME
//   x11-window-tool close-window NAME             asks it to close (WM_DELETE_WINDOW, as a window
//                                                 manager's close button does)
//   x11-window-tool screenshot OUT.png [NAME]     writes the screen (or that window's area of it)
//                                                 as an RGB PNG and prints
//                                                 "pixels W H background R G B non_background N
//                                                  colours C" (C: distinct 4-bit-per-channel colours
//                                                  among the non-background pixels with >= 50 each)
//                                                 and the pixel counts of five hue classes
// Exit status: 0 success, 1 failure (message on stderr), 2 bad command line.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace {

std::string windowName(Display* d, Window w) {
    char* name = nullptr;
    std::string out;
    if (XFetchName(d, w, &name) && name) {
        out = name;
        XFree(name);
    }
    return out;
}

// Depth-first search for a mapped window whose name contains `part`.
Window findWindow(Display* d, Window w, const std::string& part) {
    XWindowAttributes a;
    if (XGetWindowAttributes(d, w, &a) && a.map_state == IsViewable && windowName(d, w).find(part) != std::string::npos)
        return w;
    Window root, parent, *children = nullptr;
    unsigned n = 0;
    Window found = 0;
    if (XQueryTree(d, w, &root, &parent, &children, &n)) {
        for (unsigned i = 0; i < n && !found; ++i) found = findWindow(d, children[i], part);
        if (children) XFree(children);
    }
    return found;
}

uint32_t crc32(const unsigned char* p, size_t n, uint32_t c = 0xffffffffu) {
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c;
}

void be32(std::string& s, uint32_t v) {
    for (int k = 3; k >= 0; --k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

void chunk(std::ofstream& f, const char* type, const std::string& data) {
    std::string c;
    be32(c, static_cast<uint32_t>(data.size()));
    c += type;
    c += data;
    const uint32_t crc = ~crc32(reinterpret_cast<const unsigned char*>(c.data()) + 4, c.size() - 4);
    be32(c, crc);
    f.write(c.data(), static_cast<std::streamsize>(c.size()));
}

// A PNG of 8-bit RGB rows, zlib stream of stored (uncompressed) deflate blocks.
bool writePng(const std::string& path, int w, int h, const std::vector<unsigned char>& rgb) {
    std::string raw;
    for (int y = 0; y < h; ++y) {
        raw.push_back(0);  // filter: none
        raw.append(reinterpret_cast<const char*>(&rgb[3 * static_cast<size_t>(w) * y]), 3 * static_cast<size_t>(w));
    }
    std::string z = "\x78\x01";
    uint32_t a = 1, b = 0;
    for (unsigned char ch : raw) {
        a = (a + ch) % 65521;
        b = (b + a) % 65521;
    }
    for (size_t pos = 0; pos < raw.size() || pos == 0;) {
        const size_t len = std::min<size_t>(65535, raw.size() - pos);
        const bool last = pos + len >= raw.size();
        z.push_back(last ? 1 : 0);
        z.push_back(static_cast<char>(len & 0xff));
        z.push_back(static_cast<char>(len >> 8));
        z.push_back(static_cast<char>(~len & 0xff));
        z.push_back(static_cast<char>((~len >> 8) & 0xff));
        z.append(raw, pos, len);
        pos += len;
        if (last) break;
    }
    be32(z, (b << 16) | a);
    std::ofstream f(path, std::ios::binary);
    if (!f) return false;
    f.write("\x89PNG\r\n\x1a\n", 8);
    std::string ihdr;
    be32(ihdr, static_cast<uint32_t>(w));
    be32(ihdr, static_cast<uint32_t>(h));
    ihdr += std::string("\x08\x02\x00\x00\x00", 5);
    chunk(f, "IHDR", ihdr);
    chunk(f, "IDAT", z);
    chunk(f, "IEND", "");
    return static_cast<bool>(f);
}

int screenshot(Display* d, const std::string& out, const std::string& name) {
    const Window root = DefaultRootWindow(d);
    XWindowAttributes a;
    XGetWindowAttributes(d, root, &a);
    int x0 = 0, y0 = 0, w = a.width, h = a.height;
    if (!name.empty()) {  // only that window's area of the screen
        const Window win = findWindow(d, root, name);
        if (!win) {
            std::fprintf(stderr, "x11-window-tool: no window named '*%s*'\n", name.c_str());
            return 1;
        }
        XWindowAttributes wa;
        XGetWindowAttributes(d, win, &wa);
        Window child;
        XTranslateCoordinates(d, win, root, 0, 0, &x0, &y0, &child);
        w = std::min(wa.width, a.width - x0);
        h = std::min(wa.height, a.height - y0);
    }
    XImage* img = XGetImage(d, root, x0, y0, static_cast<unsigned>(w), static_cast<unsigned>(h), AllPlanes, ZPixmap);
    if (!img) {
        std::fprintf(stderr, "x11-window-tool: XGetImage failed\n");
        return 1;
    }
    std::vector<unsigned char> rgb(3 * static_cast<size_t>(w) * h);
    std::map<uint32_t, long> counts;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const unsigned long p = XGetPixel(img, x, y);
            const unsigned char r = static_cast<unsigned char>((p & img->red_mask) >> __builtin_ctzl(img->red_mask));
            const unsigned char g = static_cast<unsigned char>((p & img->green_mask) >> __builtin_ctzl(img->green_mask));
            const unsigned char b = static_cast<unsigned char>((p & img->blue_mask) >> __builtin_ctzl(img->blue_mask));
            unsigned char* o = &rgb[3 * (static_cast<size_t>(w) * y + x)];
            o[0] = r, o[1] = g, o[2] = b;
            ++counts[(uint32_t(r) << 16) | (uint32_t(g) << 8) | b];
        }
    XDestroyImage(img);
    uint32_t background = 0;
    long most = -1;
    for (const auto& [c, n] : counts)
        if (n > most) most = n, background = c;
    long nonBackground = 0;
    std::map<uint32_t, long> coarse;
    for (const auto& [c, n] : counts) {
        if (c == background) continue;
        nonBackground += n;
        coarse[((c >> 20) & 0xf) << 8 | ((c >> 12) & 0xf) << 4 | ((c >> 4) & 0xf)] += n;
    }
    int colours = 0;
    for (const auto& [c, n] : coarse)
        if (n >= 50) ++colours;
    // Pixels by hue class (what the scenes use: payload green, rope purple at half the colour
    // scale, hook yellow, trolley blue, steel grey).
    long green = 0, purple = 0, yellow = 0, blue = 0, grey = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) {
        const int r = rgb[i], g = rgb[i + 1], b = rgb[i + 2];
        if (((uint32_t(r) << 16) | (uint32_t(g) << 8) | uint32_t(b)) == background) continue;
        if (g > r + 40 && g > b + 20) ++green;
        else if (r > g + 20 && b > g + 20) ++purple;
        else if (r > 150 && g > 110 && b < 90 && r - g < 90) ++yellow;
        else if (b > r + 40 && b > g + 30) ++blue;
        else if (std::abs(r - g) < 12 && std::abs(g - b) < 16 && r > 40 && r < 200) ++grey;
    }
    if (!writePng(out, w, h, rgb)) {
        std::fprintf(stderr, "x11-window-tool: cannot write %s\n", out.c_str());
        return 1;
    }
    std::printf("pixels %d %d background %u %u %u non_background %ld colours %d green %ld purple %ld yellow %ld "
                "blue %ld grey %ld\n",
                w, h, background >> 16, (background >> 8) & 0xff, background & 0xff, nonBackground, colours, green,
                purple, yellow, blue, grey);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: x11-window-tool wait-window NAME SECONDS | close-window NAME | screenshot OUT.png [NAME]\n");
        return 2;
    }
    Display* d = XOpenDisplay(nullptr);
    if (!d) {
        std::fprintf(stderr, "x11-window-tool: cannot open display '%s'\n", std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "");
        return 1;
    }
    const std::string cmd = argv[1];
    int status = 2;
    if (cmd == "wait-window" && argc == 4) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(std::atof(argv[3]));
        status = 1;
        while (std::chrono::steady_clock::now() < until) {
            if (findWindow(d, DefaultRootWindow(d), argv[2])) {
                status = 0;
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        if (status) std::fprintf(stderr, "x11-window-tool: no window named '*%s*' within %s s\n", argv[2], argv[3]);
    } else if (cmd == "close-window" && argc == 3) {
        const Window w = findWindow(d, DefaultRootWindow(d), argv[2]);
        if (!w) {
            std::fprintf(stderr, "x11-window-tool: no window named '*%s*'\n", argv[2]);
            status = 1;
        } else {
            XEvent e;
            std::memset(&e, 0, sizeof e);
            e.xclient.type = ClientMessage;
            e.xclient.window = w;
            e.xclient.message_type = XInternAtom(d, "WM_PROTOCOLS", False);
            e.xclient.format = 32;
            e.xclient.data.l[0] = static_cast<long>(XInternAtom(d, "WM_DELETE_WINDOW", False));
            e.xclient.data.l[1] = CurrentTime;
            XSendEvent(d, w, False, NoEventMask, &e);
            XSync(d, False);
            status = 0;
        }
    } else if (cmd == "screenshot" && (argc == 3 || argc == 4)) {
        status = screenshot(d, argv[2], argc == 4 ? argv[3] : "");
    } else {
        std::fprintf(stderr, "x11-window-tool: bad command line\n");
    }
    XCloseDisplay(d);
    return status;
}
