// The OSMesa backend: Mesa's off-screen context (llvmpipe), dlopen'ed only when chosen, so that no build needs
// libOSMesa to link and a machine without it still runs on EGL.
#include <dlfcn.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>

#include "context_backend.h"

namespace rt::gpu {

namespace {

// OSMesa, declared here (osmesa.h would pull in GL/gl.h, which clashes with glad). Values from GL/osmesa.h.
namespace osmesa {
using Context = struct osmesa_context*;
using Proc = void (*)();
constexpr int kFormat = 0x22, kDepthBits = 0x30, kProfile = 0x33, kCoreProfile = 0x34, kMajor = 0x36, kMinor = 0x37;
constexpr unsigned kRgba = 0x1908, kUnsignedByte = 0x1401;
using CreateContextAttribsFn = Context (*)(const int*, Context);
using MakeCurrentFn = unsigned char (*)(Context, void*, unsigned, int, int);
using DestroyContextFn = void (*)(Context);
using GetProcAddressFn = Proc (*)(const char*);
}  // namespace osmesa

struct OsmesaContext final : GpuContext::Impl {
    // libOSMesa stays loaded: unloading Mesa (and its LLVM) while anything may still refer to it is not worth it.
    osmesa::Context context = nullptr;
    std::vector<std::uint8_t> buffer = std::vector<std::uint8_t>(16 * 16 * 4);   // a 16x16 colour buffer, unused
    osmesa::MakeCurrentFn make_current_fn = nullptr;
    osmesa::DestroyContextFn destroy = nullptr;
    osmesa::GetProcAddressFn get_proc = nullptr;

    ~OsmesaContext() override {
        if (context) destroy(context);
    }
    void make_native_current() override {
        if (!make_current_fn(context, buffer.data(), osmesa::kUnsignedByte, 16, 16))
            throw std::runtime_error("OSMesaMakeCurrent failed");
    }
    int load_gl_functions() override {
        // glad takes a plain function pointer: hand it this context's GetProcAddress through a static.
        static osmesa::GetProcAddressFn get = nullptr;
        get = get_proc;
        return gladLoadGL([](const char* name) { return reinterpret_cast<GLADapiproc>(get(name)); });
    }
};

// A broken Mesa (GALLIUM_DRIVER naming a driver that does not exist, a half-installed libgallium) crashes inside
// OSMesaCreateContextAttribs instead of returning null. So the first context is made in a child process first: if
// the child dies or hangs, the run fails with one line instead of a segfault. It costs one extra context
// creation (tens of milliseconds on llvmpipe), only when OSMesa is the backend.
void probe_in_child(osmesa::CreateContextAttribsFn create, osmesa::MakeCurrentFn make_current, const int* attribs) {
    const pid_t child = fork();
    if (child < 0) return;   // cannot probe: try for real
    if (child == 0) {
        std::vector<std::uint8_t> buffer(16 * 16 * 4);
        const osmesa::Context c = create(attribs, nullptr);
        _exit(c && make_current(c, buffer.data(), osmesa::kUnsignedByte, 16, 16) ? 0 : 3);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    int status = 0;
    while (waitpid(child, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
            throw std::runtime_error("OSMesa: creating a context did not finish in 60 s");
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (WIFSIGNALED(status)) {
        const char* driver = std::getenv("GALLIUM_DRIVER");
        throw std::runtime_error(std::string("OSMesa: creating a context crashed (") + strsignal(WTERMSIG(status)) +
                                 ")" + (driver ? std::string(": is GALLIUM_DRIVER=") + driver + " a Mesa driver?"
                                               : std::string(": is Mesa installed completely?")));
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 3)
        throw std::runtime_error("OSMesa: OSMesaCreateContextAttribs(4.5 core) failed");
}

}  // namespace

std::unique_ptr<GpuContext::Impl> create_osmesa_context(bool debug) {
    (void)debug;   // OSMesa has no debug-context attribute; GL_KHR_debug output still works
    // RT_OSMESA_LIBRARY names another libOSMesa (a Mesa built by hand; the tests name a missing one).
    const char* override = std::getenv("RT_OSMESA_LIBRARY");
    const std::string name = override && *override ? override : "libOSMesa.so.8";
    void* lib = open_backend_library("OSMesa", name);
    auto impl = std::make_unique<OsmesaContext>();
    auto create = reinterpret_cast<osmesa::CreateContextAttribsFn>(dlsym(lib, "OSMesaCreateContextAttribs"));
    impl->make_current_fn = reinterpret_cast<osmesa::MakeCurrentFn>(dlsym(lib, "OSMesaMakeCurrent"));
    impl->destroy = reinterpret_cast<osmesa::DestroyContextFn>(dlsym(lib, "OSMesaDestroyContext"));
    impl->get_proc = reinterpret_cast<osmesa::GetProcAddressFn>(dlsym(lib, "OSMesaGetProcAddress"));
    if (!create || !impl->make_current_fn || !impl->destroy || !impl->get_proc)
        throw std::runtime_error("OSMesa: " + name + " lacks OSMesaCreateContextAttribs and friends");
    const int attribs[] = {osmesa::kFormat, int(osmesa::kRgba), osmesa::kDepthBits, 24,
                           osmesa::kProfile, osmesa::kCoreProfile, osmesa::kMajor, 4, osmesa::kMinor, 5, 0};
    probe_in_child(create, impl->make_current_fn, attribs);
    impl->context = create(attribs, nullptr);
    if (!impl->context) throw std::runtime_error("OSMesa: OSMesaCreateContextAttribs(4.5 core) failed");
    impl->make_native_current();
    impl->backend = "osmesa";
    return impl;
}

}  // namespace rt::gpu
