"""The viewer tests' harness: a viewer process under a virtual display, reading its stdout; PNG reading and
comparison; xdotool input; scratch directories. Used by viewer_test.py and stress_test.py."""
import ctypes
import ctypes.util
import os
import queue
import shutil
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from image_files import decode_png  # noqa: E402

SKIP = 77
SCREEN = "-screen 0 1600x1000x24"
# -noreset: the X resources set for the hidpi case must outlive the client that sets them.
SCREENS = {"hidpi": "-screen 0 2600x1700x24 -noreset"}
HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "viewer_scene.xml")
# Where the image area's centre is in the viewer's initial 1280x800 window: right of the 400-pixel panels.
IMAGE_CENTRE = (840, 400)


class Failure(Exception):
    pass


# ---------------------------------------------------------------------------------------------- PNG files

def read_png(path):
    """(width, height, bytes RGB) of an 8-bit RGB or RGBA, non-interlaced PNG."""
    with open(path, "rb") as f:
        data = f.read()
    try:
        width, height, channels, pixels = decode_png(data)
    except ValueError as error:
        raise Failure(f"{path}: {error}") from None
    if channels == 4:
        rgb = bytearray(width * height * 3)
        for c in range(3):
            rgb[c::3] = pixels[c::4]
        pixels = bytes(rgb)
    return width, height, pixels


def compare_png(a_path, b_path):
    """(max channel difference, fraction of pixels that differ at all)."""
    wa, ha, a = read_png(a_path)
    wb, hb, b = read_png(b_path)
    if (wa, ha) != (wb, hb):
        raise Failure(f"{a_path} is {wa}x{ha} but {b_path} is {wb}x{hb}")
    if a == b:
        return 0, 0.0  # the usual answer, without a loop over every pixel
    worst, differing = 0, 0
    for i in range(0, len(a), 3):
        d = max(abs(a[i] - b[i]), abs(a[i + 1] - b[i + 1]), abs(a[i + 2] - b[i + 2]))
        worst = max(worst, d)
        differing += d > 0
    return worst, differing / (wa * ha)


def expect_same(a, b, tolerance=1):
    worst, fraction = compare_png(a, b)
    if worst > tolerance:
        raise Failure(f"{a} and {b} differ by up to {worst} per channel ({fraction:.2%} of pixels), allowed {tolerance}")
    print(f"  same: {os.path.basename(a)} = {os.path.basename(b)} (max difference {worst})")


def expect_different(a, b, min_fraction=0.02):
    worst, fraction = compare_png(a, b)
    if fraction < min_fraction:
        raise Failure(f"{a} and {b} should show different images, but only {fraction:.2%} of pixels differ")
    print(f"  different: {os.path.basename(a)} vs {os.path.basename(b)} ({fraction:.1%} of pixels)")


# ------------------------------------------------------------------------------------------ the viewer

def viewer_environment():
    """The environment for a rayview that opens a window. Under ASan, scripts/run-sanitizers sets
    RAYVIEW_VIEWER_PRELOAD to the ASan runtime and Mesa's DRI driver: preloaded, the driver stays mapped
    until the leak check at exit, so the blocks its globals still point to are not reported as leaks (they
    are when glXDestroyContext has unloaded it), and what is reported can be named (tests/lsan.supp).
    Only the rayview process gets it, never xdotool or Xvfb."""
    preload = os.environ.get("RAYVIEW_VIEWER_PRELOAD")
    return dict(os.environ, LD_PRELOAD=preload) if preload else None


class Viewer:
    """A running `rayview`, its stdout read line by line in the background."""

    def __init__(self, rayview, arguments, workdir):
        self.command = [rayview] + arguments
        print("  $ " + " ".join(self.command))
        self.process = subprocess.Popen(self.command, cwd=workdir, stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE, text=True, bufsize=1, env=viewer_environment())
        self.lines, self.stdout, self.stderr = queue.Queue(), [], []
        threading.Thread(target=self._read, args=(self.process.stdout, self.stdout, self.lines), daemon=True).start()
        threading.Thread(target=self._read, args=(self.process.stderr, self.stderr, None), daemon=True).start()

    @staticmethod
    def _read(stream, store, lines):
        for line in stream:
            store.append(line.rstrip("\n"))
            if lines is not None:
                lines.put(line.rstrip("\n"))

    def output(self):
        return "stdout:\n  " + "\n  ".join(self.stdout) + "\nstderr:\n  " + "\n  ".join(self.stderr)

    def wait_for(self, prefix, timeout=60.0, accept=lambda line: True):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                line = self.lines.get(timeout=0.1)
            except queue.Empty:
                if self.process.poll() is not None and self.lines.empty():
                    raise Failure(f"rayview exited ({self.process.returncode}) before printing '{prefix}'\n" +
                                  self.output())
                continue
            if line.startswith(prefix) and accept(line):
                print("  < " + line)
                return line
        raise Failure(f"no '{prefix}' line from rayview within {timeout} s\n" + self.output())

    def wait_final(self, after_generation=0, timeout=60.0):
        line = self.wait_for("final pass generation", timeout, lambda l: int(l.split()[-1]) > after_generation)
        return int(line.split()[-1])

    def finish(self, timeout=30.0):
        try:
            code = self.process.wait(timeout)
        except subprocess.TimeoutExpired:
            self.process.kill()
            raise Failure("rayview did not exit\n" + self.output())
        time.sleep(0.1)  # let the reader threads drain
        return code

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


def run_script(rayview, arguments, work, what="the script", timeout=120):
    """Runs the viewer with `arguments` (a --script among them) until the script quits; fails naming `what` and
    the exit code, with the viewer's output, unless it exits 0. Returns the finished Viewer (its stdout lines)."""
    viewer = Viewer(rayview, arguments, work)
    try:
        code = viewer.finish(timeout=timeout)
    finally:
        viewer.kill()
    if code != 0:
        raise Failure(f"{what} failed ({code})\n" + viewer.output())
    return viewer


def run(command, **kwargs):
    print("  $ " + " ".join(command))
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)
    if result.returncode != 0:
        raise Failure(f"{' '.join(command)} failed ({result.returncode}):\n{result.stdout}{result.stderr}")
    return result.stdout


def render_headless(rayview, scene, output, options=()):
    run([rayview, "render", scene, "-o", output, "--quiet", *options])
    return output


def xdotool(*arguments):
    if not shutil.which("xdotool"):
        raise Failure("xdotool is not installed (apt-get install xdotool)")
    return run(["xdotool"] + [str(a) for a in arguments]).strip()


def viewer_window(viewer):
    """The X window of the viewer process, focused for keyboard input (Xvfb has no window manager)."""
    window = xdotool("search", "--sync", "--onlyvisible", "--pid", viewer.process.pid).split()[0]
    xdotool("mousemove", "--window", window, *IMAGE_CENTRE)
    xdotool("windowfocus", "--sync", window)
    return window


def key(window, keys):
    xdotool("mousemove", "--window", window, *IMAGE_CENTRE)
    xdotool("key", "--clearmodifiers", keys)


def fresh_directory(output, case):
    directory = os.path.join(output, case)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    return directory


def copy_scene(directory, name="scene.xml"):
    path = os.path.join(directory, name)
    shutil.copyfile(SCENE, path)
    return path


# ------------------------------------------------------------------------------------------- the cases

def last_generation(viewer):
    finals = [int(line.split()[-1]) for line in viewer.stdout if line.startswith("final pass generation")]
    return finals[-1] if finals else 0

def title_of(window):
    return xdotool("getwindowname", window)

def save_now(viewer, window):
    key(window, "ctrl+s")
    return viewer.wait_for("saved ").split(" ", 1)[1]

def image_point(column, row):
    """Window coordinates of the centre of image pixel (column, row) of the 480x300 test scene in the initial
    1280x800 window: the image fills the 880x800 area right of the 400-pixel panels, scaled by 880/480."""
    scale = 880 / 480
    return round(400 + (column + 0.5) * scale), round((800 - 300 * scale) / 2 + (row + 0.5) * scale)

def set_screen_dpi(dpi):
    """Xft.dpi in the root window's resources, as a desktop sets it: GLFW derives the content scale from it."""
    libx11 = ctypes.util.find_library("X11")
    if not libx11:
        raise Failure("libX11 not found")
    x = ctypes.cdll.LoadLibrary(libx11)
    x.XOpenDisplay.restype = ctypes.c_void_p
    x.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x.XDefaultRootWindow.restype = ctypes.c_ulong
    x.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
    x.XChangeProperty.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_int,
                                  ctypes.c_int, ctypes.c_char_p, ctypes.c_int]
    x.XCloseDisplay.argtypes = [ctypes.c_void_p]
    display = x.XOpenDisplay(None)
    if not display:
        raise Failure("cannot open the X display")
    resources = f"Xft.dpi:\t{dpi}\n".encode()
    xa_resource_manager, xa_string, prop_mode_replace = 23, 31, 0  # predefined atoms (X.h, Xatom.h)
    x.XChangeProperty(display, x.XDefaultRootWindow(display), xa_resource_manager, xa_string, 8, prop_mode_replace,
                      resources, len(resources))
    x.XCloseDisplay(display)

def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    # utime and stime are fields 14 and 15 of the file, 12 and 13 after the command name.
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def flip_then_difference(viewer, window, held_shot, difference_shot, seconds):
    """While a script sleeps between screenshots: hold Space (the reference) until `held_shot` is taken, release
    it, press D (the difference view) and wait for `difference_shot`. Each key must take effect within `seconds`."""
    xdotool("keydown", "space")
    try:
        viewer.wait_for("showing reference", timeout=seconds)
        viewer.wait_for(f"screenshot {held_shot}", timeout=2 * seconds)
    finally:
        xdotool("keyup", "space")
    viewer.wait_for("showing render", timeout=seconds)
    xdotool("mousemove", "--window", window, *IMAGE_CENTRE)
    xdotool("key", "d")
    viewer.wait_for("showing difference", timeout=seconds)
    viewer.wait_for(f"screenshot {difference_shot}", timeout=2 * seconds)


# ---------------------------------------------------------------------------------------------- running a case

def run_case(script, cases, args, screen=SCREEN, needs_display=True):
    """The main of viewer_test.py and stress_test.py: re-runs `script` (with the same arguments) under
    `xvfb-run` unless already there (SKIP when xvfb-run is missing), then runs cases[args.case](args, work)
    in a fresh directory under args.output, with the viewer's settings kept there. Returns the exit code."""
    if needs_display and not os.environ.get("RAYVIEW_UNDER_XVFB"):
        xvfb_run = shutil.which("xvfb-run")
        if not xvfb_run:
            print("SKIPPED: xvfb-run is not installed (apt-get install xvfb); the viewer tests need a virtual display")
            return SKIP
        environment = dict(os.environ, RAYVIEW_UNDER_XVFB="1")
        return subprocess.call([xvfb_run, "-a", "-s", screen, sys.executable, os.path.abspath(script)] + sys.argv[1:],
                               env=environment)

    work = fresh_directory(os.path.abspath(args.output), args.case)
    # Recent files and any other settings go to the case's directory, never to the user's ~/.config.
    os.environ["XDG_CONFIG_HOME"] = os.path.join(work, "config")
    # The recovery files of unsaved edits too, never the user's ~/.local/state.
    os.environ["XDG_STATE_HOME"] = os.path.join(work, "state")
    started = time.monotonic()
    try:
        cases[args.case](args, work)
    except Failure as failure:
        print(f"FAILED {args.case}: {failure}")
        return 1
    print(f"passed {args.case} in {time.monotonic() - started:.1f} s (files in {work})")
    return 0
