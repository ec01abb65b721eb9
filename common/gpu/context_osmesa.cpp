// The OSMesa backend: Mesa's off-screen context (llvmpipe), dlopen'ed only when chosen, so that no build needs
// libOSMesa to link and a machine without it still runs on EGL.
#include <dlfcn.h>

#include <stdexcept>

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

}  // namespace

std::unique_ptr<GpuContext::Impl> create_osmesa_context(bool debug) {
    (void)debug;   // OSMesa has no debug-context attribute; GL_KHR_debug output still works
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib) throw std::runtime_error(std::string("OSMesa: dlopen(libOSMesa.so.8): ") + dlerror());
    auto impl = std::make_unique<OsmesaContext>();
    auto create = reinterpret_cast<osmesa::CreateContextAttribsFn>(dlsym(lib, "OSMesaCreateContextAttribs"));
    impl->make_current_fn = reinterpret_cast<osmesa::MakeCurrentFn>(dlsym(lib, "OSMesaMakeCurrent"));
    impl->destroy = reinterpret_cast<osmesa::DestroyContextFn>(dlsym(lib, "OSMesaDestroyContext"));
    impl->get_proc = reinterpret_cast<osmesa::GetProcAddressFn>(dlsym(lib, "OSMesaGetProcAddress"));
    if (!create || !impl->make_current_fn || !impl->destroy || !impl->get_proc)
        throw std::runtime_error("OSMesa: libOSMesa.so.8 lacks OSMesaCreateContextAttribs and friends");
    const int attribs[] = {osmesa::kFormat, int(osmesa::kRgba), osmesa::kDepthBits, 24,
                           osmesa::kProfile, osmesa::kCoreProfile, osmesa::kMajor, 4, osmesa::kMinor, 5, 0};
    impl->context = create(attribs, nullptr);
    if (!impl->context) throw std::runtime_error("OSMesa: OSMesaCreateContextAttribs(4.5 core) failed");
    impl->make_native_current();
    impl->backend = "osmesa";
    return impl;
}

}  // namespace rt::gpu
