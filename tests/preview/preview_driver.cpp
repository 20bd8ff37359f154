// Drives an interactive kiri-preview as a user would, through the X server (XTest): waits for
// its window, then mouse drags, keys and a window resize, each followed by F12 so that the
// screenshots record what it did, then Ctrl+S and closing the window. Run under xvfb-run by
// preview_test; it only drives and reports, the test checks the files.
//
//   preview_driver WORK_DIR PREVIEW_EXE [ARGS...]   (the preview runs in WORK_DIR)
//
// Exit 0 when every step happened and the preview exited with 0; otherwise 1 with the step.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XTest.h>
#include <X11/keysym.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

Display* dpy = nullptr;
Window window = 0;
pid_t child = -1;
fs::path work;

[[noreturn]] void fail(const std::string& what)
{
    std::fprintf(stderr, "preview_driver: %s\n", what.c_str());
    if (child > 0)
        kill(child, SIGTERM);
    std::exit(1);
}

Window find_window(Window w)
{
    char* name = nullptr;
    if (XFetchName(dpy, w, &name) && name) {
        const bool match = std::strncmp(name, "kiri preview", 12) == 0;
        XFree(name);
        if (match)
            return w;
    }
    Window root, parent, *children = nullptr;
    unsigned n = 0;
    Window found = 0;
    if (XQueryTree(dpy, w, &root, &parent, &children, &n)) {
        for (unsigned i = 0; i < n && !found; ++i)
            found = find_window(children[i]);
        if (children)
            XFree(children);
    }
    return found;
}

void pause_for(std::chrono::milliseconds ms)
{
    XSync(dpy, False);
    std::this_thread::sleep_for(ms);
}

void move_to(int x, int y)
{
    XWindowAttributes a;
    XGetWindowAttributes(dpy, window, &a);
    int rx = 0, ry = 0;
    Window unused;
    XTranslateCoordinates(dpy, window, DefaultRootWindow(dpy), x, y, &rx, &ry, &unused);
    XTestFakeMotionEvent(dpy, -1, rx, ry, CurrentTime);
    pause_for(30ms);
}

void key(KeySym sym, KeySym modifier = NoSymbol)
{
    const KeyCode code = XKeysymToKeycode(dpy, sym), mod = modifier ? XKeysymToKeycode(dpy, modifier) : 0;
    if (mod)
        XTestFakeKeyEvent(dpy, mod, True, CurrentTime);
    XTestFakeKeyEvent(dpy, code, True, CurrentTime);
    pause_for(150ms);  // held across a few frames of the preview's event loop
    XTestFakeKeyEvent(dpy, code, False, CurrentTime);
    if (mod)
        XTestFakeKeyEvent(dpy, mod, False, CurrentTime);
    pause_for(50ms);
}

void drag(unsigned button, int x0, int y0, int x1, int y1)
{
    move_to(x0, y0);
    XTestFakeButtonEvent(dpy, button, True, CurrentTime);
    pause_for(100ms);
    for (int i = 1; i <= 10; ++i) {
        move_to(x0 + (x1 - x0) * i / 10, y0 + (y1 - y0) * i / 10);
        pause_for(60ms);
    }
    XTestFakeButtonEvent(dpy, button, False, CurrentTime);
    pause_for(100ms);
}

void wait_for(const fs::path& file, const std::string& step)
{
    for (int i = 0; i < 1200; ++i) {  // two minutes: llvmpipe on a loaded machine
        if (fs::exists(file))
            return;
        int status = 0;
        if (waitpid(child, &status, WNOHANG) == child) {
            child = -1;
            fail(step + ": the preview exited (status " + std::to_string(status) + ")");
        }
        std::this_thread::sleep_for(100ms);
    }
    fail(step + ": no " + file.string());
}

// F12, then wait for the n-th screenshot.
void screenshot(int n, const std::string& stem, const std::string& step)
{
    move_to(40, 300);  // keyboard focus follows the pointer without a window manager
    key(XK_F12);
    wait_for(work / (stem + "-preview-" + std::to_string(n) + ".png"), step);
    std::printf("%d: %s\n", n, step.c_str());
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 3) {
        std::fprintf(stderr, "usage: preview_driver WORK_DIR PREVIEW_EXE [ARGS...]\n");
        return 2;
    }
    work = argv[1];
    std::string stem;
    for (int i = 3; i < argc && stem.empty(); ++i)
        if (std::string(argv[i]).ends_with(".json"))
            stem = fs::path(argv[i]).stem().string();
    dpy = XOpenDisplay(nullptr);
    if (!dpy)
        fail("no X display (run under xvfb-run)");
    int event, error, major, minor;
    if (!XTestQueryExtension(dpy, &event, &error, &major, &minor))
        fail("the X server has no XTest extension");
    child = fork();
    if (child == 0) {
        if (chdir(work.c_str()) != 0)
            _exit(127);
        execv(argv[2], argv + 2);
        _exit(127);
    }
    for (int i = 0; i < 600 && !window; ++i) {
        std::this_thread::sleep_for(100ms);
        window = find_window(DefaultRootWindow(dpy));
    }
    if (!window)
        fail("no preview window within a minute");
    XSelectInput(dpy, window, StructureNotifyMask);
    pause_for(500ms);

    screenshot(1, stem, "start");
    // The panel sits at the right: drags in the left half reach the camera.
    drag(Button1, 150, 250, 330, 250);
    screenshot(2, stem, "orbit (left drag)");
    drag(Button3, 150, 250, 150, 330);
    screenshot(3, stem, "pan (right drag)");
    key(XK_3);
    screenshot(4, stem, "bookmark 3");
    key(XK_h);
    screenshot(5, stem, "panel hidden (H)");
    XResizeWindow(dpy, window, 700, 420);
    pause_for(1000ms);
    screenshot(6, stem, "resized to 700x420");
    key(XK_1);
    pause_for(2000ms);  // past the reduced frame of the jump
    screenshot(7, stem, "bookmark 1");
    key(XK_m);
    pause_for(6000ms);  // the medium and 20k particles on the worker (~1 s on llvmpipe's machine)
    screenshot(8, stem, "render mode particles (M)");
    pause_for(1000ms);
    screenshot(9, stem, "the same view again");
    move_to(40, 300);
    key(XK_s, XK_Control_L);
    wait_for(work / (stem + "-edited.json"), "save (Ctrl+S)");
    std::printf("saved\n");

    // Close as a window manager would.
    Atom protocols = XInternAtom(dpy, "WM_PROTOCOLS", False), del = XInternAtom(dpy, "WM_DELETE_WINDOW", False);
    XEvent e{};
    e.xclient.type = ClientMessage;
    e.xclient.window = window;
    e.xclient.message_type = protocols;
    e.xclient.format = 32;
    e.xclient.data.l[0] = long(del);
    e.xclient.data.l[1] = CurrentTime;
    XSendEvent(dpy, window, False, NoEventMask, &e);
    XSync(dpy, False);
    int status = 0;
    for (int i = 0; i < 600; ++i) {
        if (waitpid(child, &status, WNOHANG) == child) {
            XCloseDisplay(dpy);
            if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
                fail("the preview exited with status " + std::to_string(status));
            std::printf("closed\n");
            return 0;
        }
        std::this_thread::sleep_for(100ms);
    }
    fail("the preview did not close within a minute");
}
