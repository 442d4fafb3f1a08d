//! A small XML element tree and its text: the three formats' writers build
//! one and print it.

/// An XML element: its name, attributes in order, text, comments and children.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Element {
    /// Tag name.
    pub name: String,
    /// Attributes, in the order written.
    pub attributes: Vec<(String, String)>,
    /// Text content, escaped when written.
    pub text: Option<String>,
    /// Child elements and comments, in order.
    pub children: Vec<Node>,
}

/// A child of an element.
#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    /// An element.
    Element(Element),
    /// A comment (`--` in it is written `- -`).
    Comment(String),
}

impl Element {
    /// An element with no attributes or children.
    pub fn new(name: &str) -> Self {
        Element { name: name.into(), ..Default::default() }
    }

    /// Adds an attribute.
    pub fn attr(mut self, key: &str, value: impl Into<String>) -> Self {
        self.attributes.push((key.into(), value.into()));
        self
    }

    /// Sets the text.
    pub fn text(mut self, t: impl Into<String>) -> Self {
        self.text = Some(t.into());
        self
    }

    /// Adds a child.
    pub fn child(mut self, e: Element) -> Self {
        self.children.push(Node::Element(e));
        self
    }

    /// Adds a child in place.
    pub fn push(&mut self, e: Element) {
        self.children.push(Node::Element(e));
    }

    /// Adds a comment in place.
    pub fn comment(&mut self, c: impl Into<String>) {
        self.children.push(Node::Comment(c.into()));
    }

    /// The document: an XML declaration and the element, indented by two spaces.
    pub fn document(&self) -> String {
        let mut out = String::from("<?xml version=\"1.0\"?>\n");
        self.write(0, &mut out);
        out
    }

    fn write(&self, depth: usize, out: &mut String) {
        let pad = "  ".repeat(depth);
        out.push_str(&pad);
        out.push('<');
        out.push_str(&self.name);
        for (k, v) in &self.attributes {
            out.push_str(&format!(" {k}=\"{}\"", escape(v)));
        }
        if self.children.is_empty() && self.text.is_none() {
            out.push_str("/>\n");
            return;
        }
        out.push('>');
        if let Some(t) = &self.text {
            out.push_str(&escape(t));
        }
        if self.children.is_empty() {
            out.push_str(&format!("</{}>\n", self.name));
            return;
        }
        out.push('\n');
        for c in &self.children {
            match c {
                Node::Element(e) => e.write(depth + 1, out),
                Node::Comment(t) => {
                    out.push_str(&format!("{pad}  <!-- {} -->\n", escape(&t.replace("--", "- -"))));
                }
            }
        }
        out.push_str(&format!("{pad}</{}>\n", self.name));
    }
}

/// `&`, `<`, `>` and `"` as entities.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A number as every XML client reads it back to the same double: the
/// shortest round-trip decimals, with an exponent outside $[10^{-4}, 10^{9})$.
///
/// # Example
/// ```
/// use flexure::export::xml::number;
/// assert_eq!((number(0.015), number(1.4558e-7), number(-0.0), number(2.0)), ("0.015".into(), "1.4558e-7".into(), "0".into(), "2".into()));
/// ```
pub fn number(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-4..1e9).contains(&a) { format!("{x}") } else { format!("{x:e}") }
}

/// Numbers separated by spaces.
pub fn numbers(xs: &[f64]) -> String {
    xs.iter().map(|x| number(*x)).collect::<Vec<_>>().join(" ")
}
