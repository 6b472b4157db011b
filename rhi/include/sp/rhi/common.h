// Basic vocabulary of the ShadowPort RHI: handles, errors, the object base class.
//
// Porting rule of thumb: `ID3D11Foo` -> `sp::Foo`, `D3D11_BAR` -> `sp::BAR`, `DXGI_FORMAT_X` ->
// `sp::FORMAT_X`. COM pointers become `sp::Ref<T>` (shared ownership) or stay raw pointers with
// AddRef/Release, and a failed HRESULT becomes a thrown `sp::Error` whose message names the call
// and the object.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace sp {

template <class T>
using Ref = std::shared_ptr<T>;

// Every validation failure has a stable id (for tests and scripts) and a message for people.
#define SP_ERROR_IDS(X)                                                                        \
  X(DEVICE_CREATION_FAILED)     /* backend could not start (no driver, no EGL, ...) */         \
  X(DEVICE_API_ERROR)           /* the driver rejected a call ShadowPort thought valid */      \
  X(INVALID_ARGUMENT)           /* null pointer, count mismatch, enum out of range */          \
  X(INVALID_DESC)               /* a field of a *_DESC is not allowed */                       \
  X(SIZE_OUT_OF_RANGE)          /* zero or over-limit width/height/bytes/mips/samples */       \
  X(FORMAT_UNSUPPORTED)         /* the format cannot be used this way on this device */        \
  X(BIND_FLAGS_INVALID)         /* resource lacks (or may not have) a bind flag */             \
  X(USAGE_INVALID)              /* usage / CPU access combination not allowed */               \
  X(INITIAL_DATA_INVALID)       /* missing or ill-sized SUBRESOURCE_DATA */                    \
  X(VIEW_FORMAT_INCOMPATIBLE)   /* view format outside the resource's typeless family */       \
  X(VIEW_DIMENSION_INVALID)     /* view dimension does not fit the resource */                 \
  X(SUBRESOURCE_OUT_OF_RANGE)   /* mip/slice/element range outside the resource */             \
  X(SHADER_COMPILE_FAILED)      /* HLSL front end, legaliser, validator or GLSL failure */     \
  X(SHADER_STAGE_MISMATCH)      /* pixel bytecode given to CreateVertexShader, ... */          \
  X(INPUT_LAYOUT_MISMATCH)      /* element not in the VS input signature, bad format ... */    \
  X(SHADER_INTERFACE_MISMATCH)  /* PS reads a semantic the VS does not write */                \
  X(SLOT_OUT_OF_RANGE)          /* StartSlot + Num beyond the D3D11 slot count */              \
  X(UNBOUND_RESOURCE)           /* a register the bound shader reads has nothing bound */      \
  X(RESOURCE_TYPE_MISMATCH)     /* bound view's dimension/type differs from the shader's */    \
  X(SAMPLE_COUNT_MISMATCH)      /* RTV/DSV/shader disagree on MSAA sample counts */            \
  X(OUTPUT_MISMATCH)            /* render targets of different size, RTV+UAV slot overlap */   \
  X(DRAW_STATE_INVALID)         /* no VS, no input layout, missing vertex/index buffer, ... */ \
  X(COPY_INVALID)               /* Copy* between incompatible resources */                     \
  X(MAP_INVALID)                /* map type not allowed for the usage, double map, ... */      \
  X(QUERY_INVALID)              /* Begin on a timestamp, GetData size mismatch, ... */         \
  X(NOT_SUPPORTED)              /* valid D3D11 but not supported by this backend/driver */

enum class ErrorId : uint32_t {
#define SP_X(name) name,
  SP_ERROR_IDS(SP_X)
#undef SP_X
};

std::string_view ErrorIdName(ErrorId id);

// HRESULT, for the D3D11-shaped overloads (out-pointer Create* calls, D3DCompile-style
// compilation) that return a status instead of throwing, so ported code keeps its
// `if (FAILED(hr))` / V_RETURN structure. Values are Windows' own.
using HRESULT = int32_t;
inline constexpr HRESULT S_OK = 0;
inline constexpr HRESULT S_FALSE = 1;
inline constexpr HRESULT E_NOTIMPL = int32_t(0x80004001u);
inline constexpr HRESULT E_FAIL = int32_t(0x80004005u);
inline constexpr HRESULT E_OUTOFMEMORY = int32_t(0x8007000Eu);
inline constexpr HRESULT E_INVALIDARG = int32_t(0x80070057u);
inline constexpr HRESULT DXGI_ERROR_UNSUPPORTED = int32_t(0x887A0004u);
inline constexpr bool SUCCEEDED(HRESULT hr) { return hr >= 0; }
inline constexpr bool FAILED(HRESULT hr) { return hr < 0; }

// Thrown by every API call that D3D11 would fail (E_INVALIDARG etc.) or whose misuse the D3D11
// debug layer reports. what() reads:
//   "[SP_VIEW_FORMAT_INCOMPATIBLE] CreateShaderResourceView(Texture2D 'shadow map'): ..."
class Error : public std::runtime_error {
 public:
  Error(ErrorId id, std::string call, std::string object, std::string detail);
  ErrorId id() const { return id_; }
  const std::string& call() const { return call_; }
  const std::string& object() const { return object_; }
  const std::string& detail() const { return detail_; }

 private:
  ErrorId id_;
  std::string call_, object_, detail_;
};

// Messages that D3D11's debug layer would print without failing the call (automatic unbinding of
// a resource bound for output, ...) and driver validation output.
enum class MessageSeverity : uint8_t { Info, Warning, Error };

class Device;

namespace detail {
struct BackendObject;  // a backend's data of an object (private)
struct ObjectAccess;
}  // namespace detail

// Base of every device child (resources, views, states, shaders, queries).
class Object : public std::enable_shared_from_this<Object> {
 public:
  virtual ~Object();
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  // SetPrivateData(WKPDID_D3DDebugObjectName) equivalent; used in error messages and passed on
  // to the driver's debug names.
  void SetDebugName(std::string_view name);
  const std::string& GetDebugName() const { return name_; }

  // COM references, for code that keeps raw pointers (`sp::Texture2D* m_pTex; SAFE_RELEASE(m_pTex)`).
  // They count apart from Ref<T> owners: while any is held the object keeps itself alive, and it
  // is destroyed when the last Ref and the last COM reference are gone. Release returns the COM
  // references left (D3D11 returns its total count) and throws sp::Error when none is held.
  // Like the device, not thread-safe.
  uint32_t AddRef();
  uint32_t Release();

  // "Texture2D 'shadow map' (1024x1024 R32_TYPELESS)" or "Texture2D #7 (...)" when unnamed.
  std::string Describe() const;
  virtual const char* TypeName() const = 0;
  uint64_t UniqueId() const { return uid_; }
  Device* GetDevice() const { return device_; }

 protected:
  explicit Object(Device* device);
  virtual std::string DescribeShape() const { return {}; }
  virtual void OnDebugNameChanged() {}

 private:
  friend class Device;
  friend struct detail::ObjectAccess;
  Device* device_;
  uint64_t uid_;
  std::string name_;
  std::unique_ptr<detail::BackendObject> backend_;
  uint32_t comRefs_ = 0;
  std::shared_ptr<Object> comSelf_;  // held while comRefs_ > 0
};

// The out-pointer of the D3D11-shaped calls: a COM-style `T**` (it receives an AddRef'd pointer,
// to be Released, as from D3D11), a `Ref<T>*`, or null (`NULL`, `nullptr`). Arrays (the *Get*
// calls) are indexed.
template <class T>
class OutPtr {
 public:
  OutPtr(T** raw) : raw_(raw) {}
  OutPtr(Ref<T>* ref) : ref_(ref) {}
  OutPtr(std::nullptr_t) {}
  // NULL as ported code writes it (an integer constant 0 in C++).
  template <class Int>
    requires std::is_integral_v<Int>
  OutPtr(Int) {}

  bool IsNull() const { return !raw_ && !ref_; }
  void Set(size_t i, Ref<T> value) const {
    if (raw_) {
      if (value) value->AddRef();
      raw_[i] = value.get();
    } else if (ref_) {
      ref_[i] = std::move(value);
    }
  }
  void Set(Ref<T> value) const { Set(0, std::move(value)); }

 private:
  T** raw_ = nullptr;
  Ref<T>* ref_ = nullptr;
};

}  // namespace sp
