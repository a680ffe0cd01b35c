//! The part of XLA's FFI C ABI (`xla/ffi/api/c_api.h`, API version 0.3, shipped with jaxlib)
//! that lekalo's handlers use, mirrored with `#[repr(C)]`, and the one place that reads a raw
//! call frame: [`handle`] turns it into a [`Call`] of checked slices, answers XLA's metadata
//! query, runs a handler body with panics caught, and turns an error message into an
//! `XLA_FFI_Error`.
//!
//! Layout notes (`c_api.h`): every struct starts with `struct_size` (the offset of its last
//! field plus that field's size, `XLA_FFI_STRUCT_SIZE`) and `extension_start`; C enums are
//! `int`. Arguments and results are `XLA_FFI_Buffer`s (dtype, data, rank, dims); attributes are
//! named, and a scalar attribute is an `XLA_FFI_Scalar` (dtype, pointer to the value).

use std::ffi::{c_char, c_int, c_void, CString};
use std::mem::{offset_of, size_of};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// `XLA_FFI_API_MAJOR` / `XLA_FFI_API_MINOR` of the header the structs below mirror.
const API_MAJOR: c_int = 0;
const API_MINOR: c_int = 3;

/// `XLA_FFI_Extension_Metadata`.
const EXTENSION_METADATA: c_int = 1;
/// `XLA_FFI_ExecutionStage_EXECUTE`.
const STAGE_EXECUTE: c_int = 3;
/// `XLA_FFI_ArgType_BUFFER` (= `XLA_FFI_RetType_BUFFER`).
const BUFFER: c_int = 1;
/// `XLA_FFI_AttrType_SCALAR`.
const ATTR_SCALAR: c_int = 3;
/// `XLA_FFI_DataType_PRED`, `_S32`, `_S64`, `_F64`.
const DTYPE_PRED: c_int = 1;
const DTYPE_S32: c_int = 4;
const DTYPE_S64: c_int = 5;
const DTYPE_F64: c_int = 12;
/// `XLA_FFI_Error_Code_INVALID_ARGUMENT` and `_INTERNAL`.
const ERROR_INVALID_ARGUMENT: c_int = 3;
const ERROR_INTERNAL: c_int = 13;

/// `XLA_FFI_Extension_Base`.
#[repr(C)]
struct ExtensionBase {
    struct_size: usize,
    kind: c_int,
    next: *mut ExtensionBase,
}

/// `XLA_FFI_Api_Version`.
#[repr(C)]
struct ApiVersion {
    struct_size: usize,
    extension_start: *mut ExtensionBase,
    major_version: c_int,
    minor_version: c_int,
}

/// `XLA_FFI_Metadata`.
#[repr(C)]
struct Metadata {
    struct_size: usize,
    api_version: ApiVersion,
    traits: u32,
    state_type_id: i64,
}

/// `XLA_FFI_Metadata_Extension`.
#[repr(C)]
struct MetadataExtension {
    extension_base: ExtensionBase,
    metadata: *mut Metadata,
}

/// `XLA_FFI_Buffer`.
#[repr(C)]
struct Buffer {
    struct_size: usize,
    extension_start: *mut ExtensionBase,
    dtype: c_int,
    data: *mut c_void,
    rank: i64,
    dims: *const i64,
}

/// `XLA_FFI_Args` and `XLA_FFI_Rets` (the same layout).
#[repr(C)]
struct Operands {
    struct_size: usize,
    extension_start: *mut ExtensionBase,
    size: i64,
    types: *const c_int,
    buffers: *const *mut Buffer,
}

/// `XLA_FFI_ByteSpan`.
#[repr(C)]
struct ByteSpan {
    ptr: *const c_char,
    len: usize,
}

/// `XLA_FFI_Scalar`.
#[repr(C)]
struct Scalar {
    dtype: c_int,
    value: *const c_void,
}

/// `XLA_FFI_Attrs`.
#[repr(C)]
struct Attrs {
    struct_size: usize,
    extension_start: *mut ExtensionBase,
    size: i64,
    types: *const c_int,
    names: *const *const ByteSpan,
    attrs: *const *const c_void,
}

/// `XLA_FFI_CallFrame`.
#[repr(C)]
pub(crate) struct CallFrame {
    struct_size: usize,
    extension_start: *mut ExtensionBase,
    api: *const Api,
    ctx: *mut c_void,
    stage: c_int,
    args: Operands,
    rets: Operands,
    attrs: Attrs,
    future: *mut c_void,
}

/// The opaque `XLA_FFI_Error`.
#[repr(C)]
pub(crate) struct XlaError {
    _private: [u8; 0],
}

/// `XLA_FFI_Error_Create_Args`.
#[repr(C)]
struct ErrorCreateArgs {
    struct_size: usize,
    extension_start: *mut ExtensionBase,
    message: *const c_char,
    errc: c_int,
}

/// The first fields of `XLA_FFI_Api`, up to `XLA_FFI_Error_Create` (the only entry used; the
/// rest of the table is never read through this prefix).
#[repr(C)]
struct Api {
    struct_size: usize,
    extension_start: *mut ExtensionBase,
    api_version: ApiVersion,
    internal_api: *const c_void,
    error_create: Option<unsafe extern "C" fn(*mut ErrorCreateArgs) -> *mut XlaError>,
}

/// `XLA_FFI_STRUCT_SIZE` of each struct: the offset of its last field plus that field's size.
const CALL_FRAME_SIZE: usize = offset_of!(CallFrame, attrs) + size_of::<Attrs>();
const BUFFER_SIZE: usize = offset_of!(Buffer, dims) + size_of::<*const i64>();
const API_VERSION_SIZE: usize = offset_of!(ApiVersion, minor_version) + size_of::<c_int>();
const METADATA_SIZE: usize = offset_of!(Metadata, traits) + size_of::<u32>();
const METADATA_EXTENSION_SIZE: usize =
    offset_of!(MetadataExtension, metadata) + size_of::<*mut Metadata>();
const ERROR_CREATE_ARGS_SIZE: usize = offset_of!(ErrorCreateArgs, errc) + size_of::<c_int>();
const API_PREFIX_SIZE: usize =
    offset_of!(Api, error_create) + size_of::<Option<unsafe extern "C" fn()>>();

/// A float64 argument: its dimensions and its numbers (row-major, XLA's default layout for
/// `ffi_call` operands).
pub(crate) struct In<'a> {
    pub(crate) dims: &'a [i64],
    pub(crate) data: &'a [f64],
}

/// A float64 result buffer: its dimensions and its numbers, to be filled.
pub(crate) struct Out<'a> {
    pub(crate) dims: &'a [i64],
    pub(crate) data: &'a mut [f64],
}

/// A decoded call: the arguments, the results and the scalar attributes (as `i64`).
pub(crate) struct Call<'a> {
    pub(crate) args: Vec<In<'a>>,
    pub(crate) rets: Vec<Out<'a>>,
    attrs: Vec<(&'a [u8], i64)>,
}

impl Call<'_> {
    /// The integer (or boolean) attribute `name`.
    pub(crate) fn attr(&self, name: &str) -> Result<i64, String> {
        self.attrs
            .iter()
            .find(|(n, _)| *n == name.as_bytes())
            .map(|&(_, v)| v)
            .ok_or_else(|| format!("the custom call has no attribute `{name}`"))
    }
}

/// A handler body: reads `call.args` and the attributes, fills `call.rets`; an `Err` is the
/// message XLA reports.
pub(crate) type Body = fn(&mut Call<'_>) -> Result<(), String>;

/// The whole of an `XLA_FFI_Handler` around `body`: answers the metadata query (the API version
/// the structs mirror, no traits, no state), refuses a stage other than execution, decodes the
/// frame, runs `body` with panics caught, and returns null on success or an `XLA_FFI_Error`
/// (invalid argument: `target` and the message; internal: a panic).
pub(crate) fn handle(frame: *mut CallFrame, target: &str, body: Body) -> *mut XlaError {
    let outcome = catch_unwind(AssertUnwindSafe(|| match read_frame(frame) {
        Ok(Frame::Metadata) => Ok(()),
        Ok(Frame::Execute(mut call)) => body(&mut call),
        Err(message) => Err(message),
    }));
    let (code, message) = match outcome {
        Ok(Ok(())) => return std::ptr::null_mut(),
        Ok(Err(message)) => (ERROR_INVALID_ARGUMENT, format!("{target}: {message}")),
        Err(_) => (
            ERROR_INTERNAL,
            format!("{target}: internal error in lekalo (a panic); please report it"),
        ),
    };
    create_error(frame, code, &message)
}

enum Frame<'a> {
    /// XLA asked for the handler's metadata, now filled in.
    Metadata,
    Execute(Call<'a>),
}

/// Reads the call frame XLA passes: the metadata query is answered in place; otherwise the
/// buffers become slices.
#[allow(unsafe_code)]
fn read_frame<'a>(frame: *mut CallFrame) -> Result<Frame<'a>, String> {
    // SAFETY (the whole function): XLA calls a handler with a pointer to a call frame that is
    // valid, initialised and not accessed by anyone else until the handler returns
    // (`XLA_FFI_Handler` in c_api.h); the `Call` made here borrows from it and lives only inside
    // `handle`, that is inside this call. Every struct read is first checked to be at least as
    // large as the layout mirrored here (`struct_size`), as the C++ `Ffi::Call` does, so no field
    // is read past the end of what XLA allocated. Counts and ranks come from XLA and are checked
    // to be non-negative before they size a slice.
    let frame = unsafe { frame.as_ref() }.ok_or("XLA passed no call frame")?;
    if frame.struct_size < CALL_FRAME_SIZE {
        return Err(format!(
            "XLA's call frame has {} bytes, lekalo expects at least {CALL_FRAME_SIZE}: \
             the installed jaxlib is older than this lekalo supports",
            frame.struct_size
        ));
    }
    // SAFETY: as above; an extension is a linked list of structs XLA owns for the call.
    if let Some(ext) = unsafe { frame.extension_start.as_ref() } {
        if ext.kind == EXTENSION_METADATA {
            if ext.struct_size < METADATA_EXTENSION_SIZE {
                return Err("XLA's metadata extension is smaller than c_api.h's".into());
            }
            // SAFETY: an extension of kind `XLA_FFI_Extension_Metadata` is an
            // `XLA_FFI_Metadata_Extension` (c_api.h), checked large enough just above; its
            // `metadata` points to a struct the handler is asked to fill.
            let ext = unsafe { &*(ext as *const ExtensionBase).cast::<MetadataExtension>() };
            let meta = unsafe { ext.metadata.as_mut() }.ok_or("XLA's metadata query is empty")?;
            if meta.struct_size < METADATA_SIZE {
                return Err("XLA's metadata struct is smaller than c_api.h's".into());
            }
            meta.api_version = ApiVersion {
                struct_size: API_VERSION_SIZE,
                extension_start: std::ptr::null_mut(),
                major_version: API_MAJOR,
                minor_version: API_MINOR,
            };
            meta.traits = 0;
            if meta.struct_size >= size_of::<Metadata>() {
                meta.state_type_id = 0; // XLA_FFI_UNKNOWN_TYPE_ID: the handler keeps no state
            }
            return Ok(Frame::Metadata);
        }
    }
    if frame.stage != STAGE_EXECUTE {
        return Err(format!(
            "called at execution stage {}, lekalo's handlers run at the execute stage only",
            frame.stage
        ));
    }
    let args = buffers(&frame.args, "argument")?
        .into_iter()
        .map(|(dims, data, len)| {
            // SAFETY: an argument buffer holds `len` = Π dims elements of its dtype (checked
            // float64 and aligned in `buffers`) and is only read during the call.
            let data = if len == 0 {
                &[][..]
            } else {
                unsafe { std::slice::from_raw_parts(data.cast::<f64>(), len) }
            };
            In { dims, data }
        })
        .collect();
    let rets = buffers(&frame.rets, "result")?
        .into_iter()
        .map(|(dims, data, len)| {
            // SAFETY: a result buffer holds `len` elements and is written by this handler
            // alone; XLA gives each result its own buffer, distinct from the arguments (lekalo
            // declares no input-output aliasing), so the mutable slices do not overlap.
            let data = if len == 0 {
                &mut [][..]
            } else {
                unsafe { std::slice::from_raw_parts_mut(data.cast::<f64>(), len) }
            };
            Out { dims, data }
        })
        .collect();
    let attrs = attributes(&frame.attrs)?;
    Ok(Frame::Execute(Call { args, rets, attrs }))
}

/// One buffer, checked: its dimensions, its data pointer and its element count.
type RawBuffer<'a> = (&'a [i64], *mut c_void, usize);

/// The buffers of `XLA_FFI_Args` or `XLA_FFI_Rets`: dims, data pointer and element count, each
/// checked to be float64, aligned and non-null when not empty.
#[allow(unsafe_code)]
fn buffers<'a>(ops: &'a Operands, what: &str) -> Result<Vec<RawBuffer<'a>>, String> {
    let n = usize::try_from(ops.size).map_err(|_| format!("negative {what} count"))?;
    if n == 0 {
        return Ok(Vec::new());
    }
    // SAFETY: `types` and `buffers` have `size` entries (c_api.h, "length == size").
    let (types, ptrs) = unsafe {
        (
            std::slice::from_raw_parts(ops.types, n),
            std::slice::from_raw_parts(ops.buffers, n),
        )
    };
    let mut out = Vec::with_capacity(n);
    for (i, (&ty, &ptr)) in types.iter().zip(ptrs).enumerate() {
        if ty != BUFFER {
            return Err(format!("{what} {i} is not a buffer"));
        }
        // SAFETY: an entry of type BUFFER points to an `XLA_FFI_Buffer` (c_api.h).
        let b = unsafe { ptr.as_ref() }.ok_or_else(|| format!("{what} {i} is null"))?;
        if b.struct_size < BUFFER_SIZE {
            return Err(format!(
                "{what} {i}: XLA's buffer struct is smaller than c_api.h's"
            ));
        }
        if b.dtype != DTYPE_F64 {
            return Err(format!(
                "{what} {i} has XLA dtype {}, lekalo computes in float64 (dtype {DTYPE_F64})",
                b.dtype
            ));
        }
        let rank = usize::try_from(b.rank).map_err(|_| format!("{what} {i}: negative rank"))?;
        // SAFETY: `dims` has `rank` entries (c_api.h, "length == rank").
        let dims = if rank == 0 {
            &[][..]
        } else {
            unsafe { std::slice::from_raw_parts(b.dims, rank) }
        };
        let len = dims.iter().try_fold(1usize, |acc, &d| {
            usize::try_from(d).ok().and_then(|d| acc.checked_mul(d))
        });
        let len = len.ok_or_else(|| format!("{what} {i}: bad dimensions {dims:?}"))?;
        if len > 0 && (b.data.is_null() || !b.data.cast::<f64>().is_aligned()) {
            return Err(format!("{what} {i}: null or misaligned float64 data"));
        }
        out.push((dims, b.data, len));
    }
    Ok(out)
}

/// The scalar attributes, as `(name, value)`: booleans and 32/64-bit integers (the only kinds
/// lekalo's Python side passes).
#[allow(unsafe_code)]
fn attributes(attrs: &Attrs) -> Result<Vec<(&[u8], i64)>, String> {
    let n = usize::try_from(attrs.size).map_err(|_| "negative attribute count".to_string())?;
    if n == 0 {
        return Ok(Vec::new());
    }
    // SAFETY: `types`, `names` and `attrs` have `size` entries (c_api.h).
    let (types, names, values) = unsafe {
        (
            std::slice::from_raw_parts(attrs.types, n),
            std::slice::from_raw_parts(attrs.names, n),
            std::slice::from_raw_parts(attrs.attrs, n),
        )
    };
    let mut out = Vec::with_capacity(n);
    for ((&ty, &name), &value) in types.iter().zip(names).zip(values) {
        // SAFETY: a name is a byte span of `len` bytes XLA owns for the call.
        let name = unsafe { name.as_ref() }.ok_or("an attribute has no name")?;
        let name = if name.len == 0 {
            &[][..]
        } else {
            unsafe { std::slice::from_raw_parts(name.ptr.cast::<u8>(), name.len) }
        };
        if ty != ATTR_SCALAR {
            continue; // not one of lekalo's attributes; `Call::attr` reports a missing one
        }
        // SAFETY: a scalar attribute is an `XLA_FFI_Scalar` whose `value` points to one value
        // of its `dtype` (api.h, scalar attribute decoding).
        let scalar = unsafe { value.cast::<Scalar>().as_ref() }.ok_or("null attribute")?;
        let v = match scalar.dtype {
            DTYPE_PRED => i64::from(unsafe { *scalar.value.cast::<u8>() } != 0),
            DTYPE_S32 => i64::from(unsafe { scalar.value.cast::<i32>().read_unaligned() }),
            DTYPE_S64 => unsafe { scalar.value.cast::<i64>().read_unaligned() },
            _ => continue,
        };
        out.push((name, v));
    }
    Ok(out)
}

/// An `XLA_FFI_Error` with `code` and `message`, made by XLA's own `XLA_FFI_Error_Create` (which
/// copies the message); null (success) only if the frame gives no way to make one.
#[allow(unsafe_code)]
fn create_error(frame: *mut CallFrame, code: c_int, message: &str) -> *mut XlaError {
    let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
    // SAFETY: `frame` is XLA's call frame (see `read_frame`); `api` points to XLA's function
    // table, valid for the process, of which only the prefix up to `XLA_FFI_Error_Create` is
    // read, after its `struct_size` says that it is there.
    let create = unsafe { frame.as_ref() }
        .and_then(|f| unsafe { f.api.as_ref() })
        .filter(|api| api.struct_size >= API_PREFIX_SIZE)
        .and_then(|api| api.error_create);
    let Some(create) = create else {
        return std::ptr::null_mut();
    };
    let mut args = ErrorCreateArgs {
        struct_size: ERROR_CREATE_ARGS_SIZE,
        extension_start: std::ptr::null_mut(),
        message: message.as_ptr(),
        errc: code,
    };
    // SAFETY: XLA's `XLA_FFI_Error_Create` reads the arguments (valid for the call, the message
    // NUL-terminated) and returns a new error that XLA takes ownership of.
    unsafe { create(&mut args) }
}

// The sizes of c_api.h's structs on the 64-bit targets JAX supports (size_t and pointers 8
// bytes, enums 4), checked at compile time so that a mistake in a mirror above fails the build.
#[cfg(target_pointer_width = "64")]
const _: () = {
    assert!(BUFFER_SIZE == 48, "XLA_FFI_Buffer");
    assert!(API_VERSION_SIZE == 24, "XLA_FFI_Api_Version");
    assert!(METADATA_SIZE == 36, "XLA_FFI_Metadata up to traits");
    assert!(METADATA_EXTENSION_SIZE == 32, "XLA_FFI_Metadata_Extension");
    assert!(ERROR_CREATE_ARGS_SIZE == 28, "XLA_FFI_Error_Create_Args");
    assert!(CALL_FRAME_SIZE == 168, "XLA_FFI_CallFrame up to attrs");
    assert!(
        API_PREFIX_SIZE == 56,
        "XLA_FFI_Api up to XLA_FFI_Error_Create"
    );
};
