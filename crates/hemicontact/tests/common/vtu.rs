//! Reading back the `.vtu` files the library writes: the XML attributes of a named array
//! and its values, decoded from the zlib-compressed appended data with
//! `hemicontact::io::zlib_blocks::decompress`.

use hemicontact::io::zlib_blocks;

/// The `<DataArray …/>` tag of the array `name` (the first with that name).
pub fn tag<'a>(text: &'a str, name: &str) -> &'a str {
    let key = format!("Name=\"{name}\"");
    let at = text.find(&key).unwrap_or_else(|| panic!("no array {name}"));
    let start = text[..at].rfind('<').unwrap();
    &text[start..at + text[at..].find("/>").unwrap()]
}

/// The value of the attribute `attr` of a tag.
pub fn attr<'a>(tag: &'a str, attr: &str) -> &'a str {
    tag.split(&format!(" {attr}=\""))
        .nth(1)
        .unwrap_or_else(|| panic!("no attribute {attr} in {tag}"))
        .split('"')
        .next()
        .unwrap()
}

/// The raw (uncompressed) bytes of the array `name` and its VTK type.
pub fn raw(bytes: &[u8], name: &str) -> (String, Vec<u8>) {
    let marker = b"<AppendedData encoding=\"raw\">\n_";
    let start = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .expect("appended data")
        + marker.len();
    let text = String::from_utf8_lossy(&bytes[..start]);
    let tag = tag(&text, name);
    let offset: usize = attr(tag, "offset").parse().unwrap();
    let (data, _) = zlib_blocks::decompress(&bytes[start + offset..]).expect("valid block");
    (attr(tag, "type").to_string(), data)
}

/// The values of the `Float64` array `name`.
pub fn f64s(bytes: &[u8], name: &str) -> Vec<f64> {
    let (ty, data) = raw(bytes, name);
    assert_eq!(ty, "Float64", "{name}");
    data.chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// The values of the `Int32` array `name`.
pub fn i32s(bytes: &[u8], name: &str) -> Vec<i32> {
    let (ty, data) = raw(bytes, name);
    assert_eq!(ty, "Int32", "{name}");
    data.chunks(4)
        .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// The text of the `UInt8` field-data array `name` (UTF-8, ending in one NUL byte).
pub fn text(bytes: &[u8], name: &str) -> String {
    let (ty, mut data) = raw(bytes, name);
    assert_eq!(ty, "UInt8", "{name}");
    assert_eq!(data.pop(), Some(0), "{name} ends in NUL");
    String::from_utf8(data).unwrap()
}

/// The values of the `Int64` array `name`.
pub fn i64s(bytes: &[u8], name: &str) -> Vec<i64> {
    let (ty, data) = raw(bytes, name);
    assert_eq!(ty, "Int64", "{name}");
    data.chunks(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// (name, type, components) of every array of the section `section` (`PointData`,
/// `CellData`, `PPointData`, …) of a file's XML, in document order.
pub fn arrays(bytes: &[u8], section: &str) -> Vec<(String, String, usize)> {
    let text = String::from_utf8_lossy(bytes);
    let open = format!("<{section}>");
    let Some(start) = text.find(&open) else {
        return Vec::new();
    };
    let end = start + text[start..].find(&format!("</{section}>")).unwrap();
    text[start + open.len()..end]
        .lines()
        .filter(|l| l.contains("DataArray"))
        .map(|l| {
            (
                attr(l, "Name").to_string(),
                attr(l, "type").to_string(),
                attr(l, "NumberOfComponents").parse().unwrap(),
            )
        })
        .collect()
}
