//! `#[derive(Module)]`: a module's ports, registers, wires and children are declared once, by
//! an attribute on their field, and its `tick`, `visit` and `visit_bits` (the values a tracer
//! samples, statically dispatched) are generated from them, so a register added to the struct
//! is committed at the clock edge, traced and schedule-checked with no other edit. The
//! behaviour stays hand-written: an inherent `fn eval(&mut self)`.
//!
//! ```text
//! #[derive(Module)]
//! #[module(kind = "blend")]          // the kind (and, by default, the instance name:
//!                                    // `instance = "..."` names it otherwise);
//!                                    // `new` also generates `Blend::new()` (below)
//! pub struct Blend {
//!     #[input] pub a: Signal,         // Signal, [Signal; N] or Vec<Signal>
//!     #[output] pub out: Signal,
//!     #[wire] sum: Signal,            // an internal combinational value, traced
//!     #[reg] out_r: Reg,              // Reg, [Reg; N] or Vec<Reg>: ticked and traced
//!     #[child] stage: Stage,          // a Module, [M; N], Vec<M> or Option<M>: ticked, visited
//!     #[narrow] round: Narrowing,     // a named narrowing (or [_; N], Vec<_>): visited for
//!                                    // numeric coverage
//!     #[instance] name: &'static str, // optional: the instance name
//!     params: Params,                 // anything unmarked is neither ticked nor visited
//!     #[skip] probe: Signal,          // ... but a signal, register, memory, delay line,
//!                                    // narrowing or stream left unmarked is a compile
//!                                    // error unless `#[skip]` says it is left out on purpose
//! }
//! // `#[module(kind = "...", enable = self.busy.is_high())]`: a clock enable, the edge of
//! // every register and child skipped while it is low (reset still applies); in debug
//! // builds a skipped edge with a register's next value pending panics.
//! impl Blend { fn eval(&mut self) { ... } }
//! ```
//!
//! Fields are visited in declaration order. With `#[module(kind = "...", new)]` and every
//! field a marked signal or register with its format (`#[input(fmt = COLOUR)]`,
//! `#[reg(fmt = PRODUCT, reset = ...)]`, `#[reg(fmt = F, states = &["IDLE", "FETCH"])]`) or a
//! narrowing with its modes (`#[narrow(quant = Quant::Trunc, overflow = Overflow::Saturate)]`),
//! the derive also writes `pub fn new() -> Self`, each signal and narrowing named after its
//! field: the names, formats, modes and state names are then written once, in the struct. A
//! field whose type is its format (`SignalOf<F>`, `RegOf<F>`, `NarrowingOf<F>`) needs no
//! `fmt`. A module whose edge or
//! hierarchy the attributes cannot say keeps a hand-written `impl Module`.
//!
//! `#[derive(Signals)]` makes a struct of signals a port bundle (an `Option` of one: ports a
//! configuration may leave out), `#[derive(Regs)]` a struct of registers a register bundle; `#[derive(Group)]` makes a struct of children a group that
//! ticks and visits them into its owner's scope, with no scope of its own.

use proc_macro::TokenStream;
use proc_macro2::TokenStream as Tokens;
use quote::{format_ident, quote};
use syn::{parse_macro_input, Data, DeriveInput, Fields, LitStr};

/// What a field is to its module.
#[derive(Clone, Copy, PartialEq)]
enum Role {
    Input,
    Output,
    Wire,
    Reg,
    Child,
    Narrow,
    Instance,
}

const ROLES: [(&str, Role); 7] = [
    ("input", Role::Input),
    ("output", Role::Output),
    ("wire", Role::Wire),
    ("reg", Role::Reg),
    ("child", Role::Child),
    ("narrow", Role::Narrow),
    ("instance", Role::Instance),
];

/// Derives `Module` (see the crate documentation).
#[proc_macro_derive(
    Module,
    attributes(module, input, output, wire, reg, child, narrow, instance, skip)
)]
pub fn derive_module(input: TokenStream) -> TokenStream {
    let ast = parse_macro_input!(input as DeriveInput);
    expand(&ast).unwrap_or_else(|e| e.to_compile_error()).into()
}

/// Derives `Signals` for a port bundle: a struct of signals (or of bundles, arrays, vectors of
/// them) visited field by field, in order, with the direction the module's attribute gives it
/// (`#[input] pub i: BlendIn`). A bundle is written once and travels whole: to a driver, a
/// monitor, a co-simulation adapter.
#[proc_macro_derive(Signals)]
pub fn derive_signals(input: TokenStream) -> TokenStream {
    let ast = parse_macro_input!(input as DeriveInput);
    expand_signals(&ast)
        .unwrap_or_else(|e| e.to_compile_error())
        .into()
}

/// Derives `Regs` for a register bundle: a struct of registers (or of bundles, arrays,
/// vectors of them), ticked and visited field by field, in order, in the scope of the module
/// that holds it (`#[reg] held: Held`): registers with names instead of positions.
#[proc_macro_derive(Regs)]
pub fn derive_regs(input: TokenStream) -> TokenStream {
    let ast = parse_macro_input!(input as DeriveInput);
    expand_regs(&ast)
        .unwrap_or_else(|e| e.to_compile_error())
        .into()
}

/// The impl of trait `[tr, tick, visit]` (`Regs` or `Children`, for the derive `what`) whose
/// edge and visit call the same methods on every field of `ast`, in order.
fn per_field(
    ast: &DeriveInput,
    what: &str,
    [tr, tick, visit, bits]: [&str; 4],
) -> syn::Result<Tokens> {
    let fields = named_fields(ast, what)?;
    let hdl = hdl_path();
    let tr = format_ident!("{}", tr);
    let tr = quote!(#hdl::kernel::declared::#tr);
    let (tick, visit) = (format_ident!("{}", tick), format_ident!("{}", visit));
    let bits = format_ident!("{}", bits);
    let name = &ast.ident;
    let (impl_g, ty_g, where_g) = ast.generics.split_for_impl();
    let ids: Vec<_> = fields.named.iter().map(|f| &f.ident).collect();
    Ok(quote! {
        impl #impl_g #tr for #name #ty_g #where_g {
            #[inline]
            fn #tick(&mut self, reset: bool) {
                #(#tr::#tick(&mut self.#ids, reset);)*
            }
            fn #visit(&self, v: &mut dyn #hdl::kernel::Visitor) {
                #(#tr::#visit(&self.#ids, v);)*
            }
            #[inline]
            fn #bits<__F: FnMut(u64)>(&self, __f: &mut __F) {
                #(#tr::#bits(&self.#ids, __f);)*
            }
        }
    })
}

fn expand_regs(ast: &DeriveInput) -> syn::Result<Tokens> {
    per_field(
        ast,
        "Regs",
        ["Regs", "tick_regs", "visit_regs", "bits_regs"],
    )
}

/// Derives `Children` for a group of sub-modules that has no scope of its own (one MIP
/// level's units, say): every field is a child (a module, or a collection of them), ticked
/// and visited in order, straight into the scope of the module that holds the group.
#[proc_macro_derive(Group)]
pub fn derive_group(input: TokenStream) -> TokenStream {
    let ast = parse_macro_input!(input as DeriveInput);
    expand_group(&ast)
        .unwrap_or_else(|e| e.to_compile_error())
        .into()
}

fn expand_group(ast: &DeriveInput) -> syn::Result<Tokens> {
    per_field(
        ast,
        "Group",
        [
            "Children",
            "tick_children",
            "visit_children",
            "bits_children",
        ],
    )
}

/// The named fields of the struct `ast` (`what` names the derive in the error).
fn named_fields<'a>(ast: &'a DeriveInput, what: &str) -> syn::Result<&'a syn::FieldsNamed> {
    match &ast.data {
        Data::Struct(s) => match &s.fields {
            Fields::Named(f) => Ok(f),
            _ => Err(syn::Error::new_spanned(
                &ast.ident,
                format!("#[derive({what})] needs named fields"),
            )),
        },
        _ => Err(syn::Error::new_spanned(
            &ast.ident,
            format!("#[derive({what})] is for structs"),
        )),
    }
}

fn expand_signals(ast: &DeriveInput) -> syn::Result<Tokens> {
    let fields = named_fields(ast, "Signals")?;
    let hdl = hdl_path();
    let name = &ast.ident;
    let (impl_g, ty_g, where_g) = ast.generics.split_for_impl();
    let visits = fields.named.iter().map(|f| {
        let id = &f.ident;
        quote!(#hdl::kernel::declared::Signals::visit_signals(&self.#id, dir, v);)
    });
    let ids = fields.named.iter().map(|f| &f.ident);
    Ok(quote! {
        impl #impl_g #hdl::kernel::declared::Signals for #name #ty_g #where_g {
            fn visit_signals(&self, dir: #hdl::kernel::Dir, v: &mut dyn #hdl::kernel::Visitor) {
                #(#visits)*
            }
            #[inline]
            fn bits_signals<__F: FnMut(u64)>(&self, __f: &mut __F) {
                #(#hdl::kernel::declared::Signals::bits_signals(&self.#ids, __f);)*
            }
        }
    })
}

/// The path of texrtl-hdl as the deriving crate names it.
fn hdl_path() -> Tokens {
    use proc_macro_crate::{crate_name, FoundCrate};
    match crate_name("texrtl-hdl") {
        // texrtl-hdl itself (its lib names itself `hdl`, its tests depend on it as `hdl`).
        Ok(FoundCrate::Itself) => quote!(::hdl),
        // A dependency declared under its package name is named by its lib's name, `hdl`.
        Ok(FoundCrate::Name(n)) if n == "texrtl_hdl" => quote!(::hdl),
        Ok(FoundCrate::Name(n)) => {
            let id = format_ident!("{}", n);
            quote!(::#id)
        }
        Err(_) => quote!(::hdl),
    }
}

/// `#[module(kind = "...", instance = "...", enable = ..., new)]`: the kind (required: a
/// string, or a `&'static str` expression such as a generic module's `C::KIND` or a field,
/// `self.kind`), the instance name (the kind's by default), a clock enable (an expression of
/// `self`, read at the edge) and whether to generate `new`.
fn module_args(ast: &DeriveInput) -> syn::Result<ModuleArgs> {
    let (mut kind, mut instance, mut new, mut enable) = (None, None, false, None);
    for a in ast.attrs.iter().filter(|a| a.path().is_ident("module")) {
        a.parse_nested_meta(|m| {
            if m.path.is_ident("kind") {
                kind = Some(m.value()?.parse::<syn::Expr>()?);
                Ok(())
            } else if m.path.is_ident("instance") {
                instance = Some(m.value()?.parse::<LitStr>()?);
                Ok(())
            } else if m.path.is_ident("new") {
                new = true;
                Ok(())
            } else if m.path.is_ident("enable") {
                enable = Some(m.value()?.parse::<syn::Expr>()?);
                Ok(())
            } else {
                Err(m.error(
                    "expected `kind = \"...\"`, `instance = \"...\"`, `enable = ...` or `new`",
                ))
            }
        })?;
    }
    let kind = kind.ok_or_else(|| {
        syn::Error::new_spanned(
            &ast.ident,
            "#[derive(Module)] needs #[module(kind = \"...\")]",
        )
    })?;
    Ok(ModuleArgs {
        kind,
        instance,
        new,
        enable,
    })
}

/// What `#[module(...)]` says.
struct ModuleArgs {
    kind: syn::Expr,
    instance: Option<LitStr>,
    new: bool,
    /// A clock enable: the edge is skipped while it is false (and reset is not asserted).
    enable: Option<syn::Expr>,
}

/// `pub fn new() -> Self`: every field a signal or register of a declared format, named
/// after its field, registers reset to zero unless `reset` says otherwise.
fn constructor(ast: &DeriveInput, fields: &[Field], hdl: &Tokens) -> syn::Result<Tokens> {
    let unmoded = |f: &Field| f.role == Role::Narrow && (f.quant.is_none() || f.overflow.is_none());
    if named_fields(ast, "Module")?.named.len() != fields.len()
        || fields
            .iter()
            .any(|f| matches!(f.role, Role::Child | Role::Instance) || unmoded(f))
    {
        return Err(syn::Error::new_spanned(
            &ast.ident,
            "`new` needs every field a marked signal, register or narrowing (with its `quant` and `overflow`)",
        ));
    }
    let mut inits = Vec::new();
    let decl = quote!(#hdl::kernel);
    for f in fields {
        let (id, ty, name) = (&f.id, &f.ty, f.id.to_string());
        if let (Role::Narrow, Some(q), Some(o)) = (f.role, &f.quant, &f.overflow) {
            // A typed narrowing (`NarrowingOf<F>`) has its format in its type; a run-time one
            // (`Narrowing`) takes `fmt`.
            let fmt = f.fmt.iter();
            inits.push(quote!(#id: <#ty>::new(#name, #(#fmt,)* #q, #o)));
            continue;
        }
        // A `fmt = ...` builds a run-time-format field (or checks a typed one's); without it,
        // the field's type is its format (`SignalOf<F>`, `RegOf<F>`).
        let mut base = match &f.fmt {
            Some(fmt) => quote!(<#ty as #decl::Declare>::declare(#name, #fmt)),
            None => quote!(<#ty as #decl::DeclareTyped>::declare_typed(#name)),
        };
        if let Some(r) = &f.reset {
            base = quote!(#base.reset_to(#r));
        }
        if let Some(st) = &f.states {
            base = quote!(#base.with_states(#st));
        }
        inits.push(quote!(#id: #base));
    }
    let name = &ast.ident;
    Ok(quote! {
        impl #name {
            /// The module, every signal and register named after its field, in its declared format.
            pub fn new() -> Self {
                Self { #(#inits),* }
            }
        }
    })
}

/// A marked field: its name, role and what its attribute says it is made of.
struct Field {
    id: syn::Ident,
    /// The field's type.
    ty: syn::Type,
    role: Role,
    /// `fmt = EXPR`: the signal's or register's format (for the generated `new`).
    fmt: Option<syn::Expr>,
    /// `states = EXPR`: an FSM register's or signal's state names.
    states: Option<syn::Expr>,
    /// `reset = EXPR`: a register's reset value (an `Fx`), zero by default.
    reset: Option<syn::Expr>,
    /// `quant = EXPR`, `overflow = EXPR`: a narrowing's modes (for the generated `new`).
    quant: Option<syn::Expr>,
    overflow: Option<syn::Expr>,
}

/// The `fmt`, `states` and `reset` of a role attribute (`#[reg(fmt = F, states = S)]`).
fn field_args(a: &syn::Attribute, f: &mut Field) -> syn::Result<()> {
    if matches!(a.meta, syn::Meta::Path(_)) {
        return Ok(());
    }
    a.parse_nested_meta(|m| {
        let slot = if m.path.is_ident("fmt") {
            &mut f.fmt
        } else if m.path.is_ident("states") {
            &mut f.states
        } else if m.path.is_ident("reset") && f.role == Role::Reg {
            &mut f.reset
        } else if m.path.is_ident("quant") && f.role == Role::Narrow {
            &mut f.quant
        } else if m.path.is_ident("overflow") && f.role == Role::Narrow {
            &mut f.overflow
        } else {
            return Err(m.error(
                "expected `fmt = ...`, `states = ...`, (a register's) `reset = ...` or (a narrowing's) `quant = ...`, `overflow = ...`",
            ));
        };
        *slot = Some(m.value()?.parse::<syn::Expr>()?);
        Ok(())
    })
}

/// Each named field's role, in declaration order; a field with two roles is an error.
fn roles(ast: &DeriveInput) -> syn::Result<Vec<Field>> {
    let fields = named_fields(ast, "Module")?;
    let (mut out, mut unmarked) = (Vec::new(), None::<syn::Error>);
    for f in &fields.named {
        let mut found: Option<Field> = None;
        for a in &f.attrs {
            let Some(&(_, role)) = ROLES.iter().find(|(n, _)| a.path().is_ident(n)) else {
                continue;
            };
            if found.is_some() {
                return Err(syn::Error::new_spanned(a, "a field has one role"));
            }
            let id = f.ident.clone().expect("named");
            let mut field = Field {
                id,
                ty: f.ty.clone(),
                role,
                fmt: None,
                states: None,
                reset: None,
                quant: None,
                overflow: None,
            };
            field_args(a, &mut field)?;
            found = Some(field);
        }
        if found.is_none() && !f.attrs.iter().any(|a| a.path().is_ident("skip")) {
            if let Err(e) = forgotten(f) {
                match &mut unmarked {
                    None => unmarked = Some(e),
                    Some(all) => all.combine(e),
                }
            }
        }
        out.extend(found);
    }
    if let Some(e) = unmarked {
        return Err(e);
    }
    if out.iter().filter(|f| f.role == Role::Instance).count() > 1 {
        return Err(syn::Error::new_spanned(
            &ast.ident,
            "one #[instance] field at most",
        ));
    }
    Ok(out)
}

/// The kernel's types that hold a module's state or ports: a field of one of them (or of an
/// array, vector, option or tuple of them) must say what it is.
const STATE_TYPES: [&str; 9] = [
    "Signal",
    "SignalOf",
    "Reg",
    "RegOf",
    "Mem",
    "Delay",
    "Narrowing",
    "NarrowingOf",
    "Stream",
];

/// An error for an unmarked field whose type names one of [`STATE_TYPES`]: left unmarked it
/// would be neither ticked nor visited, so neither committed at the edge, traced nor checked.
fn forgotten(f: &syn::Field) -> syn::Result<()> {
    let ty = &f.ty;
    let named = quote!(#ty).into_iter().find_map(|t| match t {
        proc_macro2::TokenTree::Ident(i) if STATE_TYPES.iter().any(|s| i == s) => Some(i),
        _ => mentions(&t),
    });
    match named {
        Some(t) => Err(syn::Error::new_spanned(
            f,
            format!(
                "this field holds a {t}: mark it #[input], #[output], #[wire], #[reg], #[child] or #[narrow], or #[skip] to leave it out of tick and visit on purpose"
            ),
        )),
        None => Ok(()),
    }
}

/// The first of [`STATE_TYPES`] inside a bracketed or parenthesised group (an array's element
/// type, a tuple's).
fn mentions(t: &proc_macro2::TokenTree) -> Option<proc_macro2::Ident> {
    let proc_macro2::TokenTree::Group(g) = t else {
        return None;
    };
    g.stream().into_iter().find_map(|t| match t {
        proc_macro2::TokenTree::Ident(i) if STATE_TYPES.iter().any(|s| i == s) => Some(i),
        _ => mentions(&t),
    })
}

/// A marked field's part of the generated `tick` (registers and children only), `visit` and
/// `visit_bits`: the same fields in the same order for both walks.
fn field_code(field: &Field, hdl: &Tokens) -> (Option<Tokens>, Tokens, Tokens) {
    let decl = quote!(#hdl::kernel::declared);
    let f = &field.id;
    let each = |tr: &str, method: &str| {
        let (tr, method) = (format_ident!("{}", tr), format_ident!("{}", method));
        quote!(#decl::#tr::#method(&self.#f, __f);)
    };
    match field.role {
        Role::Reg => (
            Some(quote!(#decl::Regs::tick_regs(&mut self.#f, reset);)),
            quote!(#decl::Regs::visit_regs(&self.#f, v);),
            each("Regs", "bits_regs"),
        ),
        Role::Child => (
            Some(quote!(#decl::Children::tick_children(&mut self.#f, reset);)),
            quote!(#decl::Children::visit_children(&self.#f, v);),
            each("Children", "bits_children"),
        ),
        Role::Narrow => (
            None,
            quote!(#decl::Narrowings::visit_narrowings(&self.#f, v);),
            each("Narrowings", "bits_narrowings"),
        ),
        role => {
            let d = format_ident!(
                "{}",
                match role {
                    Role::Input => "Input",
                    Role::Output => "Output",
                    _ => "Wire",
                }
            );
            (
                None,
                quote!(#decl::Signals::visit_signals(&self.#f, #hdl::kernel::Dir::#d, v);),
                each("Signals", "bits_signals"),
            )
        }
    }
}

fn expand(ast: &DeriveInput) -> syn::Result<Tokens> {
    let ModuleArgs {
        kind,
        instance: fixed_instance,
        new,
        enable,
    } = module_args(ast)?;
    let fields = roles(ast)?;
    let hdl = hdl_path();
    let ctor = if new {
        constructor(ast, &fields, &hdl)?
    } else {
        Tokens::new()
    };
    let name = &ast.ident;
    let (impl_g, ty_g, where_g) = ast.generics.split_for_impl();
    let gate = enable.map(|e| {
        quote!(if !reset && !(#e) {
            #[cfg(debug_assertions)]
            #hdl::kernel::check_gated_edge(self);
            return;
        })
    });
    let mut instance = match &fixed_instance {
        Some(i) => quote!(#i),
        None => quote!(#kind),
    };
    let (mut ticks, mut visits, mut bits) = (Vec::new(), Vec::new(), Vec::new());
    for f in &fields {
        if f.role == Role::Instance {
            let id = &f.id;
            instance = quote!(&self.#id);
            continue;
        }
        let (tick, visit, bit) = field_code(f, &hdl);
        ticks.extend(tick);
        visits.push(visit);
        bits.push(bit);
    }
    Ok(quote! {
        #ctor
        impl #impl_g #hdl::kernel::Module for #name #ty_g #where_g {
            fn instance(&self) -> &str {
                #instance
            }
            fn kind(&self) -> &'static str {
                #kind
            }
            // The unit's own (inherent) `eval`: without one this would call itself, which
            // the lint makes a compile error.
            #[inline]
            #[deny(unconditional_recursion)]
            fn eval(&mut self) {
                Self::eval(self)
            }
            #[inline]
            fn tick(&mut self, reset: bool) {
                let _ = reset;
                #gate
                #(#ticks)*
            }
            fn visit(&self, v: &mut dyn #hdl::kernel::Visitor) {
                v.enter(#hdl::kernel::Module::instance(self), #kind);
                #(#visits)*
                v.leave();
            }
            #[inline]
            fn visit_bits<__F: FnMut(u64)>(&self, __f: &mut __F) {
                let _ = &__f;
                #(#bits)*
            }
        }
    })
}
